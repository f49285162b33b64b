// A distance field's grid samples as an NRRD volume (float32, x fastest), placed in world space.
#pragma once
#include "field/distance_field.h"
#include "io/nrrd.h"

namespace hairfit {

NrrdVolume field_to_nrrd(const DistanceField& field);

}  // namespace hairfit
