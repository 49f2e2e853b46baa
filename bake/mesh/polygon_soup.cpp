#include "bake/mesh/polygon_soup.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_parse.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

// Assigns one index per distinct value (bit-exact), in order of first appearance.
template <typename Value>
class Deduplicator {
public:
  std::uint32_t index_of(const Value& v) {
    Key key;
    std::memcpy(key.data(), &v, sizeof(Value));
    auto [it, inserted] = index_.try_emplace(key, static_cast<std::uint32_t>(values.size()));
    if (inserted) values.push_back(v);
    return it->second;
  }
  std::vector<Value> values;

private:
  static_assert(sizeof(Value) % sizeof(std::uint64_t) == 0);
  using Key = std::array<std::uint64_t, sizeof(Value) / sizeof(std::uint64_t)>;
  struct Hash {
    std::size_t operator()(const Key& key) const {
      std::uint64_t h = 0;
      for (std::uint64_t word : key) {  // splitmix64's finaliser: coordinates differ in their high bits
        h ^= word + 0x9E3779B97F4A7C15ull;
        h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
        h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
        h ^= h >> 31;
      }
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<Key, std::uint32_t, Hash> index_;
};

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::dvec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

std::string place(const char* what, std::size_t index, std::size_t line) {
  std::string s = what + (" " + std::to_string(index));
  return line > 0 ? parse::at_line(line) + ", " + s : s;
}

bool in_range(std::int64_t index, std::size_t size) {
  return index >= 0 && static_cast<std::uint64_t>(index) < size;
}

using Corner = PolygonSoup::Corner;

// Welds the corners of the triangles it is given into one indexed mesh.
class MeshAssembler {
public:
  MeshAssembler(const PolygonSoup& soup, const std::string& file) : soup_(soup), file_(file) {}

  void emit(std::array<const Corner*, 3> corners, std::size_t face) {
    Triangle t{}, uv_t{}, normal_t{};
    for (int k = 0; k < 3; ++k) {
      const Corner& corner = *corners[k];
      t[k] = positions_.index_of(soup_.positions[corner.position]);
      if (corner.uv >= 0) {
        const glm::dvec2& uv = soup_.uvs[corner.uv];
        if (!finite(uv))
          throw InputError(file_, place("face", face, soup_.face_lines[face]), "texture coordinate is not a finite number");
        uv_t[k] = uvs_.index_of(uv);
      } else {
        every_corner_has_uv_ = false;
      }
      if (corner.normal >= 0) {
        normal_t[k] = normals_.index_of(soup_.normals[corner.normal]);
      } else {
        every_corner_has_normal_ = false;
      }
    }
    mesh_.triangles.push_back(t);
    mesh_.uv_triangles.push_back(uv_t);
    mesh_.normal_triangles.push_back(normal_t);
  }

  // UVs only where every corner has one; the file's normals only where every corner has a usable one,
  // else angle-weighted ones.
  ProxyMesh finish() {
    if (mesh_.triangles.empty()) throw InputError(file_, "", "mesh has no faces");
    mesh_.positions = std::move(positions_.values);
    if (every_corner_has_uv_) {
      mesh_.uvs = std::move(uvs_.values);
    } else {
      mesh_.uv_triangles.clear();
    }
    bool normals_usable = every_corner_has_normal_;
    for (glm::dvec3& normal : normals_.values) {
      if (const std::optional<glm::dvec3> unit = unit_direction(normal)) normal = *unit;
      else normals_usable = false;
    }
    if (normals_usable) {
      mesh_.normals = std::move(normals_.values);
    } else {
      compute_angle_weighted_normals(mesh_);
    }
    return std::move(mesh_);
  }

private:
  const PolygonSoup& soup_;
  const std::string& file_;
  Deduplicator<glm::dvec3> positions_;
  Deduplicator<glm::dvec2> uvs_;
  Deduplicator<glm::dvec3> normals_;
  ProxyMesh mesh_;
  bool every_corner_has_uv_ = true;
  bool every_corner_has_normal_ = true;
};

// Face `face`'s corners (from corner `begin`) into `polygon`, a vertex repeated in a row once; throws
// where they do not make a polygon. `sorted` is scratch.
void read_polygon(const PolygonSoup& soup, const std::string& file, std::size_t face, std::size_t begin,
                  std::vector<const Corner*>& polygon, std::vector<std::int64_t>& sorted) {
  const auto where = [&] { return place("face", face, soup.face_lines[face]); };
  polygon.clear();
  for (std::size_t c = begin; c < soup.face_ends[face]; ++c) {
    const Corner& corner = soup.corners[c];
    if (!in_range(corner.position, soup.positions.size()))
      throw InputError(file, where(), "references a vertex that does not exist");
    if (corner.uv >= 0 && !in_range(corner.uv, soup.uvs.size()))
      throw InputError(file, where(), "references a texture coordinate that does not exist");
    if (corner.normal >= 0 && !in_range(corner.normal, soup.normals.size()))
      throw InputError(file, where(), "references a normal that does not exist");
    if (polygon.empty() || polygon.back()->position != corner.position) polygon.push_back(&corner);
  }
  // Some writers pad a triangle to a quad by repeating a corner ("4 a b c c"): such a face is
  // that triangle, as nobody could mean anything else by it.
  while (polygon.size() > 1 && polygon.back()->position == polygon.front()->position) polygon.pop_back();
  if (soup.face_ends[face] - begin < 3) throw InputError(file, where(), "face has fewer than 3 vertices");
  if (polygon.size() < 3)
    throw InputError(file, where(), "degenerate face: fewer than 3 distinct vertices (repeated vertex index)");
  sorted.clear();
  for (const Corner* corner : polygon) sorted.push_back(corner->position);
  std::sort(sorted.begin(), sorted.end());
  if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
    throw InputError(file, where(), "face passes through vertex " + std::to_string(*twice) + " twice (repeated vertex index)");
}

void triangulate(const PolygonSoup& soup, const std::vector<const Corner*>& polygon, std::size_t face,
                 MeshAssembler& mesh) {
  const auto position = [&](std::size_t k) { return soup.positions[polygon[k]->position]; };
  if (polygon.size() == 4 && glm::length(position(3) - position(1)) < glm::length(position(2) - position(0))) {
    // A quad is cut along its shorter diagonal: the two triangles are then the least skewed, and
    // a bent quad gets the fold that bulges least. A tie keeps the fan's diagonal 0–2.
    mesh.emit({polygon[0], polygon[1], polygon[3]}, face);
    mesh.emit({polygon[1], polygon[2], polygon[3]}, face);
  } else {
    // Larger polygons become a fan from their first corner, right for the convex ones writers emit.
    for (std::size_t k = 2; k < polygon.size(); ++k) mesh.emit({polygon[0], polygon[k - 1], polygon[k]}, face);
  }
}

}  // namespace

ProxyMesh assemble_proxy_mesh(const PolygonSoup& soup, const std::string& file) {
  for (std::size_t v = 0; v < soup.positions.size(); ++v)
    if (!finite(soup.positions[v]))
      throw InputError(file, place("vertex", v, soup.position_lines[v]), "coordinate is not a finite number");
  MeshAssembler mesh(soup, file);
  std::vector<const Corner*> polygon;
  std::vector<std::int64_t> sorted;
  std::size_t face = 0;
  for (std::size_t begin = 0; face < soup.face_ends.size(); begin = soup.face_ends[face++]) {
    read_polygon(soup, file, face, begin, polygon, sorted);
    triangulate(soup, polygon, face, mesh);
  }
  return mesh.finish();
}

}  // namespace nano::mesh
