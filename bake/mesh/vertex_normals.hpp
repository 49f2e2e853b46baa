#pragma once
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// Replaces the mesh's normals by angle-weighted vertex normals (Thürmer & Wüthrich): each
// triangle contributes its unit normal weighted by its interior angle at the vertex, so the
// result does not depend on how a region is split into triangles. One normal per position;
// normal_triangles becomes a copy of triangles. Degenerate triangles contribute nothing; a
// vertex with no usable triangle gets +z so that no NaN ever reaches the shell builder.
void compute_angle_weighted_normals(ProxyMesh& mesh);

}  // namespace nano::mesh
