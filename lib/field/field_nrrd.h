// A distance field's grid samples as an NRRD volume (float32, x fastest), placed in world space.
#pragma once
#include "field/distance_field.h"
#include "io/nrrd.h"

namespace hairfit {

// Layers of samples are converted on up to `threads` threads (each writes only its own).
NrrdVolume field_to_nrrd(const DistanceField& field, int threads = 1);

}  // namespace hairfit
