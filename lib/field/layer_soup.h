// The hair layer's boundary as one triangle soup: the hull as it is and the scalp reversed, so
// that, where the hull's rim meets the scalp's (a carved cap over its scalp), the soup is closed
// around the layer and its generalized winding number is 1 in the layer and 0 outside it.
// Where the hull encloses the head, the number is 1½ in the layer and ½ behind the scalp: there
// only crossings of the scalp decide that side.
#pragma once
#include "core/mesh.h"

namespace hairfit {

Mesh hair_layer_soup(const Mesh& hull, const Mesh& scalp);

}  // namespace hairfit
