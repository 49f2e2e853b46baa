#pragma once
// Loads a proxy mesh from OBJ, PLY, OFF, STL (parsed by OpenMesh) or Draco .drc (draco_codec.hpp).
// The OpenMesh formats are parsed by OpenMesh (confined to
// mesh_reader_openmesh.cpp); this layer keeps the raw face list as written, so check-mesh can
// still see what OpenMesh's half-edge builder would silently repair (non-manifold edges, faces
// with repeated vertices) and report it against the face index of the file.
#include <filesystem>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// Polygons are split into triangle fans, in file order, so triangle i of an all-triangle file is
// face i (0-based). Bit-identical positions are welded. Normals are taken from the file when every
// corner has one, otherwise computed (angle-weighted). Throws nano::InputError naming the file on:
// a missing or unreadable file, an unknown extension, a parse failure, a face that references a
// missing vertex, non-finite coordinates, or a file with no triangles. A mesh without UVs loads
// (has_uvs() is false) so that check-mesh can report it as a problem.
ProxyMesh read_proxy_mesh(const std::filesystem::path& path);

}  // namespace nano::mesh
