#pragma once
// What each format reader hands over: the file's polygons exactly as written (no welding, no
// triangulation, indices not yet checked), with the line each vertex and face came from. One
// assembly step turns every format's soup into a ProxyMesh, so the rules of mesh_reader.hpp are
// checked, and worded, in one place.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct PolygonSoup {
  struct Corner {
    std::int64_t position = 0;  // index into positions
    std::int64_t uv = -1;       // index into uvs, -1: none
    std::int64_t normal = -1;   // index into normals, -1: none
  };
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec2> uvs;
  std::vector<glm::dvec3> normals;  // need not be unit length
  std::vector<Corner> corners;      // the faces' corners, face after face
  std::vector<std::size_t> face_ends;  // face f owns corners [face_ends[f - 1], face_ends[f])
  // The line each position and face starts on, 0 in a binary file.
  std::vector<std::size_t> position_lines;
  std::vector<std::size_t> face_lines;

  void add_position(const glm::dvec3& p, std::size_t line = 0) {
    positions.push_back(p);
    position_lines.push_back(line);
  }
  // Closes the face made of the corners added since the previous one.
  void end_face(std::size_t line = 0) {
    face_ends.push_back(corners.size());
    face_lines.push_back(line);
  }
};

// Checks the soup and builds the mesh: the rules and the triangulation are those of
// mesh_reader.hpp. Throws InputError naming `file` and the face or vertex (and its line).
ProxyMesh assemble_proxy_mesh(const PolygonSoup& soup, const std::string& file);

// The format readers (one file each). `bytes` is the whole file; each throws InputError naming
// `file` and the line or record where it stopped understanding it.
PolygonSoup read_obj_soup(std::string_view bytes, const std::string& file);
PolygonSoup read_off_soup(std::string_view bytes, const std::string& file);
PolygonSoup read_ply_soup(std::string_view bytes, const std::string& file);
PolygonSoup read_stl_soup(std::string_view bytes, const std::string& file);
// Collada through Assimp (collada_reader.cpp): no lines to name, so errors name the face or vertex.
// Assimp runs in a process of its own, held to these limits; a crash, a failed allocation past the
// address space or the time running out there is an InputError here. The defaults are what
// nanobake uses; tests and the fuzzer shorten them.
struct ColladaImportLimits {
  std::chrono::milliseconds time{60'000};
  // Address space the import may add to what the process has when it starts: this many bytes, or
  // per_byte times the file's size when that is more.
  std::uint64_t address_space = std::uint64_t{4} << 30;
  std::uint64_t address_space_per_byte = 16;
};
PolygonSoup read_collada_soup(std::string_view bytes, const std::string& file, const ColladaImportLimits& limits = {});

}  // namespace nano::mesh
