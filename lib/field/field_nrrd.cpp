#include "field/field_nrrd.h"

#include "core/parallel.h"

namespace hairfit {

NrrdVolume field_to_nrrd(const DistanceField& field, int threads) {
  NrrdVolume volume;
  volume.sizes = field.dims();
  volume.origin = field.origin();
  volume.spacing = Vec3::Constant(field.voxel());
  volume.data.resize(static_cast<std::size_t>(field.dims().x()) * field.dims().y() * field.dims().z());
  const std::size_t layer = static_cast<std::size_t>(field.dims().x()) * field.dims().y();
  parallel_for(field.dims().z(), threads, [&](int k) {
    std::size_t at = layer * k;
    for (int j = 0; j < field.dims().y(); ++j)
      for (int i = 0; i < field.dims().x(); ++i) volume.data[at++] = static_cast<float>(field.sample(i, j, k));
  });
  return volume;
}

}  // namespace hairfit
