#pragma once
// A box compartment: the region a cellPACK recipe of its cytoplasm alone fills (its bounding box).
#include <glm/vec3.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// The box of `size` (Å) centred on the origin: 8 corners, 2 triangles per face wound outward, each
// face its own UV chart (a cell of a 3 × 2 atlas) and its own normal. Made to hold solubles; a
// membrane on its sharp edges gets the baker's remeshing.
// Throws nano::InputError when a side is not positive and finite.
ProxyMesh make_box_mesh(const glm::dvec3& size);

}  // namespace nano::mesh
