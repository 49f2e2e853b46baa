#include "bake/mesh/obj_writer.hpp"

#include <cstdio>
#include <span>

#include "common/atomic_file.hpp"

namespace nano::mesh {

namespace {
void append(std::string& out, const char* format, auto... values) {
  char line[256];
  const int n = std::snprintf(line, sizeof line, format, values...);
  out.append(line, static_cast<std::size_t>(n));
}
}  // namespace

std::string format_obj(const ProxyMesh& mesh) {
  std::string out = "# nanouniverse proxy mesh\n";
  for (const glm::dvec3& p : mesh.positions) append(out, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
  for (const glm::dvec2& t : mesh.uvs) append(out, "vt %.17g %.17g\n", t.x, t.y);
  for (const glm::dvec3& n : mesh.normals) append(out, "vn %.17g %.17g %.17g\n", n.x, n.y, n.z);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    out += 'f';
    for (int c = 0; c < 3; ++c) {
      // OBJ indices are 1-based; an absent attribute leaves its slot empty ("v//vn", "v/vt").
      append(out, " %u", mesh.triangles[t][c] + 1);
      if (mesh.has_uvs() || mesh.has_normals()) out += '/';
      if (mesh.has_uvs()) append(out, "%u", mesh.uv_triangles[t][c] + 1);
      if (mesh.has_normals()) append(out, "/%u", mesh.normal_triangles[t][c] + 1);
    }
    out += '\n';
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const ProxyMesh& mesh) {
  const std::string text = format_obj(mesh);
  write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace nano::mesh
