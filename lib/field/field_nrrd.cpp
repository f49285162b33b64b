#include "field/field_nrrd.h"

namespace hairfit {

NrrdVolume field_to_nrrd(const DistanceField& field) {
  NrrdVolume volume;
  volume.sizes = field.dims();
  volume.origin = field.origin();
  volume.spacing = Vec3::Constant(field.voxel());
  volume.data.resize(static_cast<std::size_t>(field.dims().x()) * field.dims().y() * field.dims().z());
  std::size_t at = 0;
  for (int k = 0; k < field.dims().z(); ++k)
    for (int j = 0; j < field.dims().y(); ++j)
      for (int i = 0; i < field.dims().x(); ++i) volume.data[at++] = static_cast<float>(field.sample(i, j, k));
  return volume;
}

}  // namespace hairfit
