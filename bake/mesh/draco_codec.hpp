#pragma once
// Draco (libdraco) meshes in and out: the only translation unit that includes Draco. A Draco
// mesh is quantised: positions, UVs and normals come back within half a quantisation step.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct DracoQuantisation {
  int position_bits = 16;  // per axis, over the mesh's bounding box
  int uv_bits = 14;
  int normal_bits = 12;
};

// The mesh as a Draco buffer: positions per vertex, UVs and normals per corner when present.
std::vector<std::byte> encode_draco_mesh(const ProxyMesh& mesh, const DracoQuantisation& quantisation = {});

// A Draco mesh buffer read as a proxy mesh: bit-identical positions welded, UVs and normals per
// corner (normals recomputed when absent or not usable). Throws nano::InputError naming `file` when
// Draco refuses the bytes, the buffer holds a point cloud, it declares more than 4,194,304 faces or
// 3 points a face (or metadata running past its end: both read before libdraco allocates for them),
// positions are missing or not finite, texture coordinates are not finite, or a face refers to a
// value its attribute does not hold.
ProxyMesh decode_draco_mesh(std::span<const std::byte> bytes, const std::string& file);

}  // namespace nano::mesh
