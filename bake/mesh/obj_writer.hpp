#pragma once
#include <filesystem>
#include <string>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// Wavefront OBJ text: v, vt (if the mesh has UVs), vn (if it has normals) and triangles
// "f v/vt/vn" with per-corner indices, so UV seams survive. Numbers are printed with 17
// significant digits: reading the text back gives the same doubles.
std::string format_obj(const ProxyMesh& mesh);

// Writes format_obj(mesh) to `path` atomically (nothing appears at `path` on failure).
// Throws nano::InputError naming the path when it cannot be written.
void write_obj(const std::filesystem::path& path, const ProxyMesh& mesh);

}  // namespace nano::mesh
