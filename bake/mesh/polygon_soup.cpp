#include "bake/mesh/polygon_soup.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <queue>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_parse.hpp"
#include "bake/mesh/mesh_topology_cgal.hpp"
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

// ---- Triangulating a face (mesh_reader.hpp's rules) ----
// A polygon of n corners becomes n − 2 triangles whose corners are its own, in its winding, using
// only diagonals inside it: judged in the polygon's own plane, that of its Newell normal (the
// area-weighted normal, exact for a planar polygon), and weighed by their angles in 3D.

using Index3 = std::array<std::size_t, 3>;

// The sine of a triangle's smallest angle (at most 60°, so the sines order triangles as their
// smallest angles do), from twice its area and its two longer sides: 0 for a degenerate one.
double fatness(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  std::array<double, 3> sides{glm::length(b - a), glm::length(c - b), glm::length(a - c)};
  std::sort(sides.begin(), sides.end());
  const double twice_area = glm::length(glm::cross(b - a, c - a));
  return sides[1] > 0.0 ? std::min(1.0, twice_area / (sides[1] * sides[2])) : 0.0;
}

// The corners projected into the plane of the Newell normal, counter-clockwise seen from its side;
// nullopt when the normal vanishes (collinear corners, or a polygon folded onto itself).
std::optional<std::vector<glm::dvec2>> project_to_own_plane(const std::vector<glm::dvec3>& p) {
  const std::size_t n = p.size();
  glm::dvec3 newell(0.0);
  for (std::size_t i = 0; i < n; ++i) {  // about the first corner: far-off coordinates cancel less
    const glm::dvec3 a = p[i] - p[0], b = p[(i + 1) % n] - p[0];
    newell += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  const std::optional<glm::dvec3> normal = unit_direction(newell);
  if (!normal) return std::nullopt;
  // u × v = normal. A planar polygon in a plane of constant x, y or z has its normal exactly along
  // that axis (the sums above cancel exactly), u and v are axes too, and its projection is exact.
  const glm::dvec3 m = glm::abs(*normal);
  const glm::dvec3 axis = m.x <= m.y && m.x <= m.z ? glm::dvec3(1, 0, 0) : m.y <= m.z ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  const std::optional<glm::dvec3> u = unit_direction(glm::cross(*normal, axis));
  if (!u) return std::nullopt;
  const glm::dvec3 v = glm::cross(*normal, *u);
  std::vector<glm::dvec2> projected;
  projected.reserve(n);
  for (const glm::dvec3& corner : p) projected.emplace_back(glm::dot(corner, *u), glm::dot(corner, v));
  return projected;
}

// Diagonals of a polygon in the plane (O'Rourke, "Computational Geometry in C", 1.6), with exact
// orientations of the projected coordinates: a diagonal touches the boundary only at its ends.
class PlanePolygon {
public:
  explicit PlanePolygon(const std::vector<glm::dvec2>& points) : p_(points) {}

  std::size_t size() const { return p_.size(); }
  const glm::dvec2& point(std::size_t i) const { return p_[i]; }
  int orientation(std::size_t a, std::size_t b, std::size_t c) const { return exact_orientation_2d(p_[a], p_[b], p_[c]); }

  // Corners i and j joined by a segment inside the polygon (true for its edges).
  bool diagonal(std::size_t i, std::size_t j) const {
    const std::size_t n = p_.size();
    if ((i + 1) % n == j || (j + 1) % n == i) return true;
    if (!in_cone(i, j) || !in_cone(j, i)) return false;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t l = (k + 1) % n;
      if (k == i || k == j || l == i || l == j) continue;
      if (segments_meet(i, j, k, l)) return false;
    }
    return true;
  }

private:
  // The segment from corner i towards j leaves i into the polygon's interior (strictly).
  bool in_cone(std::size_t i, std::size_t j) const {
    const std::size_t n = p_.size(), before = (i + n - 1) % n, after = (i + 1) % n;
    if (orientation(before, i, after) > 0) return orientation(i, j, before) > 0 && orientation(j, i, after) > 0;
    return !(orientation(i, j, after) >= 0 && orientation(j, i, before) >= 0);  // reflex or straight corner
  }
  bool between(std::size_t a, std::size_t b, std::size_t c) const {  // c on the line through a and b
    return std::min(p_[a].x, p_[b].x) <= p_[c].x && p_[c].x <= std::max(p_[a].x, p_[b].x) &&
           std::min(p_[a].y, p_[b].y) <= p_[c].y && p_[c].y <= std::max(p_[a].y, p_[b].y);
  }
  // Closed segments ab and cd share a point.
  bool segments_meet(std::size_t a, std::size_t b, std::size_t c, std::size_t d) const {
    if (std::max(p_[a].x, p_[b].x) < std::min(p_[c].x, p_[d].x) || std::max(p_[c].x, p_[d].x) < std::min(p_[a].x, p_[b].x) ||
        std::max(p_[a].y, p_[b].y) < std::min(p_[c].y, p_[d].y) || std::max(p_[c].y, p_[d].y) < std::min(p_[a].y, p_[b].y))
      return false;  // their boxes are apart
    const int o1 = orientation(a, b, c), o2 = orientation(a, b, d), o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && between(a, b, c)) || (o2 == 0 && between(a, b, d)) || (o3 == 0 && between(c, d, a)) ||
           (o4 == 0 && between(c, d, b));
  }
  const std::vector<glm::dvec2>& p_;
};

// Up to this many corners, the triangulation that maximises the smallest angle, by dynamic
// programming over the diagonals (O(n³)); larger polygons are cut ear by ear.
constexpr std::size_t kLargestOptimalPolygon = 64;

// Of the triangulations made of diagonals, one whose smallest 3D angle is largest and, among
// those, whose sum of each triangle's fatness is largest (fat triangles where the smallest angle
// is forced elsewhere). Empty when there is none (the projection is not a simple polygon).
std::vector<Index3> optimal_triangulation(const std::vector<glm::dvec3>& p, const PlanePolygon& plane) {
  const std::size_t n = p.size();
  // Which pairs of corners are diagonals: all of them when the polygon is convex (every corner a
  // left turn, every corner left of the first side, the fan from corner 0 counter-clockwise: the
  // corners sweep once around it within half a turn), else each checked against every side.
  bool convex = true;
  for (std::size_t i = 0; i < n && convex; ++i)
    convex = plane.orientation((i + n - 1) % n, i, (i + 1) % n) > 0 && (i < 2 || plane.orientation(0, 1, i) > 0) &&
             (i < 2 || i + 1 >= n || plane.orientation(0, i, i + 1) > 0);
  std::vector<char> diagonal(n * n, 1);
  if (!convex)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) diagonal[i * n + j] = plane.diagonal(i, j);
  const auto usable = [&](std::size_t i, std::size_t k, std::size_t j) {
    return diagonal[i * n + k] && diagonal[k * n + j] && (convex || plane.orientation(i, k, j) > 0);
  };
  constexpr double none = -std::numeric_limits<double>::infinity();
  // Pass 1: the largest smallest fatness over the sub-polygon i..j (closed by the diagonal i-j).
  std::vector<double> worst(n * n, none);
  for (std::size_t i = 0; i + 1 < n; ++i) worst[i * n + i + 1] = std::numeric_limits<double>::infinity();
  for (std::size_t span = 2; span < n; ++span)
    for (std::size_t i = 0; i + span < n; ++i) {
      const std::size_t j = i + span;
      if (!diagonal[i * n + j]) continue;
      double best = none;
      for (std::size_t k = i + 1; k < j; ++k)
        if (usable(i, k, j) && std::min(worst[i * n + k], worst[k * n + j]) > best)
          best = std::max(best, std::min({worst[i * n + k], worst[k * n + j], fatness(p[i], p[k], p[j])}));
      worst[i * n + j] = best;
    }
  const double bound = worst[n - 1];  // the sub-polygon 0..n−1 is the whole polygon
  if (bound == none) return {};
  // Pass 2: among triangulations whose triangles all keep that (to rounding), the fattest.
  const double floor = bound - 1e-12;
  std::vector<double> fat(n * n, none);
  std::vector<std::size_t> split(n * n, 0);
  for (std::size_t i = 0; i + 1 < n; ++i) fat[i * n + i + 1] = 0.0;
  for (std::size_t span = 2; span < n; ++span)
    for (std::size_t i = 0; i + span < n; ++i) {
      const std::size_t j = i + span;
      if (!diagonal[i * n + j]) continue;
      for (std::size_t k = i + 1; k < j; ++k) {
        if (!usable(i, k, j) || fat[i * n + k] == none || fat[k * n + j] == none) continue;
        const double f = fatness(p[i], p[k], p[j]);
        if (f < floor) continue;
        const double sum = fat[i * n + k] + fat[k * n + j] + f;
        if (sum > fat[i * n + j]) fat[i * n + j] = sum, split[i * n + j] = k;
      }
    }
  if (fat[n - 1] == none) return {};
  std::vector<Index3> triangles;
  std::vector<std::pair<std::size_t, std::size_t>> pending{{0, n - 1}};
  while (!pending.empty()) {
    const auto [i, j] = pending.back();
    pending.pop_back();
    if (j - i < 2) continue;
    const std::size_t k = split[i * n + j];
    triangles.push_back({i, k, j});
    pending.emplace_back(k, j);
    pending.emplace_back(i, k);
  }
  std::sort(triangles.begin(), triangles.end());  // a fixed order: by first, then second corner
  return triangles;
}

// Ear clipping, each time the fattest ear (largest smallest 3D angle). A corner is an ear when its
// triangle is counter-clockwise and holds no reflex (or straight) corner, found through a grid of
// them; clipping an ear changes only its neighbours' status, so the whole takes about n log n.
// Should no ear be left (a projection that is not a simple polygon), the rest becomes a fan.
std::vector<Index3> ear_clipping(const std::vector<glm::dvec3>& p, const PlanePolygon& plane) {
  const std::size_t n = p.size();
  std::vector<std::size_t> next(n), prev(n);
  for (std::size_t i = 0; i < n; ++i) next[i] = (i + 1) % n, prev[i] = (i + n - 1) % n;
  std::vector<char> reflex(n), clipped(n, 0);
  for (std::size_t i = 0; i < n; ++i) reflex[i] = plane.orientation(prev[i], i, next[i]) <= 0;

  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) lo = glm::min(lo, plane.point(i)), hi = glm::max(hi, plane.point(i));
  const std::size_t side = std::max<std::size_t>(1, std::size_t(std::sqrt(double(n))));
  const auto cell = [&](double x, double low, double high) {
    const double t = high > low ? (x - low) / (high - low) * double(side) : 0.0;
    return std::min(side - 1, std::size_t(std::max(0.0, t)));
  };
  std::vector<std::vector<std::size_t>> cells(side * side);  // the reflex corners, by cell
  for (std::size_t i = 0; i < n; ++i)
    if (reflex[i]) cells[cell(plane.point(i).y, lo.y, hi.y) * side + cell(plane.point(i).x, lo.x, hi.x)].push_back(i);

  struct Ear {
    double fatness;
    std::size_t corner;
    std::uint32_t stamp;
    bool operator<(const Ear& o) const { return fatness < o.fatness || (fatness == o.fatness && corner > o.corner); }
  };
  std::priority_queue<Ear> ears;
  std::vector<std::uint32_t> stamp(n, 0);  // a corner's ears judged before its last judgement are stale
  const auto judge = [&](std::size_t i) {
    ++stamp[i];
    const std::size_t a = prev[i], b = next[i];
    if (plane.orientation(a, i, b) <= 0) return;
    const glm::dvec2 low = glm::min(plane.point(a), glm::min(plane.point(i), plane.point(b)));
    const glm::dvec2 high = glm::max(plane.point(a), glm::max(plane.point(i), plane.point(b)));
    for (std::size_t y = cell(low.y, lo.y, hi.y); y <= cell(high.y, lo.y, hi.y); ++y)
      for (std::size_t x = cell(low.x, lo.x, hi.x); x <= cell(high.x, lo.x, hi.x); ++x)
        for (std::size_t k : cells[y * side + x])
          if (!clipped[k] && reflex[k] && k != a && k != i && k != b && plane.orientation(a, i, k) >= 0 &&
              plane.orientation(i, b, k) >= 0 && plane.orientation(b, a, k) >= 0)
            return;
    ears.push({fatness(p[a], p[i], p[b]), i, stamp[i]});
  };
  for (std::size_t i = 0; i < n; ++i) judge(i);

  std::vector<Index3> triangles;
  std::size_t some = 0;  // a corner not yet clipped
  for (std::size_t left = n; left > 3; --left) {
    while (!ears.empty() && (clipped[ears.top().corner] || ears.top().stamp != stamp[ears.top().corner])) ears.pop();
    if (ears.empty()) {  // the last resort: a fan over what is left
      for (std::size_t k = next[next[some]]; k != some; k = next[k]) triangles.push_back({some, prev[k], k});
      return triangles;
    }
    const std::size_t i = ears.top().corner, a = prev[i], b = next[i];
    ears.pop();
    triangles.push_back({a, i, b});
    clipped[i] = 1;
    next[a] = b, prev[b] = a;
    if (some == i) some = b;
    for (std::size_t k : {a, b})
      if (reflex[k]) reflex[k] = plane.orientation(prev[k], k, next[k]) <= 0;
    judge(a), judge(b);
  }
  triangles.push_back({prev[some], some, next[some]});
  return triangles;
}

// A polygon of 5 or more corners, as triangles of corner indices in its winding.
std::vector<Index3> triangulate_polygon(const std::vector<glm::dvec3>& p) {
  const std::size_t n = p.size();
  if (const std::optional<std::vector<glm::dvec2>> projected = project_to_own_plane(p)) {
    const PlanePolygon plane(*projected);
    if (n <= kLargestOptimalPolygon)
      if (std::vector<Index3> triangles = optimal_triangulation(p, plane); !triangles.empty()) return triangles;
    return ear_clipping(p, plane);
  }
  std::vector<Index3> fan;  // no plane to judge diagonals in: the last resort
  for (std::size_t k = 2; k < n; ++k) fan.push_back({0, k - 1, k});
  return fan;
}

void triangulate(const PolygonSoup& soup, const std::vector<const Corner*>& polygon, std::size_t face,
                 MeshAssembler& mesh) {
  const auto position = [&](std::size_t k) { return soup.positions[polygon[k]->position]; };
  if (polygon.size() == 3) {
    mesh.emit({polygon[0], polygon[1], polygon[2]}, face);
  } else if (polygon.size() == 4) {
    // A quad is cut along its shorter diagonal: the two triangles are then the least skewed, and
    // a bent quad gets the fold that bulges least. A tie keeps the fan's diagonal 0–2. A concave
    // quad is cut along the diagonal inside it.
    bool cut_1_3 = glm::length(position(3) - position(1)) < glm::length(position(2) - position(0));
    const std::vector<glm::dvec3> corners{position(0), position(1), position(2), position(3)};
    if (const std::optional<std::vector<glm::dvec2>> projected = project_to_own_plane(corners)) {
      const PlanePolygon plane(*projected);
      if (cut_1_3 ? !plane.diagonal(1, 3) && plane.diagonal(0, 2) : !plane.diagonal(0, 2) && plane.diagonal(1, 3))
        cut_1_3 = !cut_1_3;
    }
    if (cut_1_3) {
      mesh.emit({polygon[0], polygon[1], polygon[3]}, face);
      mesh.emit({polygon[1], polygon[2], polygon[3]}, face);
    } else {
      mesh.emit({polygon[0], polygon[1], polygon[2]}, face);
      mesh.emit({polygon[0], polygon[2], polygon[3]}, face);
    }
  } else {
    std::vector<glm::dvec3> corners;
    corners.reserve(polygon.size());
    for (std::size_t k = 0; k < polygon.size(); ++k) corners.push_back(position(k));
    for (const Index3& t : triangulate_polygon(corners)) mesh.emit({polygon[t[0]], polygon[t[1]], polygon[t[2]]}, face);
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
