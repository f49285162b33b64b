// The stages' options as bytes: what each stage's cache key hashes (stage_plan.h). Every member
// that can change a stage's value is written, doubles bit for bit; names that only label error
// messages are not, so a renamed input file keeps its entries.
#pragma once
#include <cstdint>
#include <optional>

#include "field/distance_field.h"
#include "guides/density_term.h"
#include "guides/guides.h"
#include "pipeline/byte_stream.h"
#include "pipeline/stage_options.h"
#include "scalp/roots.h"
#include "strands/strands.h"

namespace hairfit {

void encode(ByteWriter& out, const FieldSpec& spec);
void encode(ByteWriter& out, const RootOptions& options);
void encode(ByteWriter& out, const RootSettings& settings);
void encode(ByteWriter& out, const HairMaterial& material);
void encode(ByteWriter& out, const RodDiscretisation& rod);
void encode(ByteWriter& out, const PreguideOptions& options);
void encode(ByteWriter& out, const GuideOptions& options);
void encode(ByteWriter& out, const DensityGridSpec& grid);
void encode(ByteWriter& out, const GuideDensitySettings& settings);
void encode(ByteWriter& out, const WispShape& wisp);
void encode(ByteWriter& out, const StrandOptions& options);

// An optional part of a stage's options: whether it is there, then its value.
template <class T>
void encode(ByteWriter& out, const std::optional<T>& part) {
  out.put<std::uint8_t>(part.has_value());
  if (part) encode(out, *part);
}

}  // namespace hairfit
