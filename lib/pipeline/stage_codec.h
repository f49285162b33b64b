// Binary form of every stage value, for the stage cache: encode(x) then decode gives back a value
// equal bit for bit (every double, every index, every flag), so a cached run is byte-identical to
// a cold one. The layout is native little-endian and changes with kStageCodecVersion; decoding
// throws CodecError on anything that is not exactly one encoded value.
#pragma once
#include <string>
#include <string_view>

#include "density/grid.h"
#include "field/distance_field.h"
#include "guides/guides.h"
#include "pipeline/byte_stream.h"
#include "scalp/chart.h"
#include "scalp/roots.h"
#include "strands/strands.h"

namespace hairfit {

// Bump when any layout below changes (old cache entries then simply miss).
inline constexpr int kStageCodecVersion = 6;

void encode(ByteWriter& out, const DistanceField& field);
void encode(ByteWriter& out, const ScalpChart& chart);
void encode(ByteWriter& out, const Roots& roots);
void encode(ByteWriter& out, const Clusters& clusters);
void encode(ByteWriter& out, const PreguideRoots& roots);
void encode(ByteWriter& out, const PreGuides& preguides);
void encode(ByteWriter& out, const Guides& guides);
void encode(ByteWriter& out, const Strands& strands);
void encode(ByteWriter& out, const DensityGrid& grid);

DistanceField decode_distance_field(ByteReader& in);
ScalpChart decode_scalp_chart(ByteReader& in);
Roots decode_roots(ByteReader& in);
Clusters decode_clusters(ByteReader& in);
PreguideRoots decode_preguide_roots(ByteReader& in);
PreGuides decode_preguides(ByteReader& in);
Guides decode_guides(ByteReader& in);
Strands decode_strands(ByteReader& in);
DensityGrid decode_density_grid(ByteReader& in);

// One value alone: encode to bytes, or decode bytes that must hold exactly one value.
template <class T>
std::string encode_value(const T& value) {
  ByteWriter out;
  encode(out, value);
  return out.take();
}
template <class T, class Decode>
T decode_value(std::string_view bytes, Decode decode) {
  ByteReader in(bytes);
  T value = decode(in);
  in.expect_end();
  return value;
}

}  // namespace hairfit
