#include "bake/shell/membrane_pruning.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <glm/gtc/quaternion.hpp>

#include "bake/mesh/mesh_edges.hpp"
#include "bake/tiles/collision_shape.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"
#include "shared/render_membrane_filter.h"

namespace nano::shell {
namespace {

using glm::dmat3;
using glm::dvec3;

// One owned copy where the triangle places it. A whole 1 µm cell checks 10^7 of them at once, so
// what the Wang tile instance says (its flat pose) is looked up, not kept: 96 bytes a copy.
struct Placed {
  dvec3 centre{0.0};         // compartment space, in double: far-off cells lose nothing to float
  glm::mat3 rotation{1.f};   // the atom test's own precision
  std::uint32_t triangle = 0;
  std::uint32_t key = 0;     // membrane_copy_key(slot, instance)
  std::uint32_t type = 0;
  std::uint32_t island = 0;  // UV island of the triangle: copies of one island share one flat tiling
  glm::ivec2 cell{0};        // its tile's cell in that island's unwrapped tiling
  std::uint16_t tile = 0, instance = 0;
  bool alternate = false;    // tiles::Instance::alternate: shown only if it fits where its original clashes
  bool has_alternate = false;
};
static_assert(sizeof(Placed) <= 96);

// Where the island's flat tiling has the copy: tile-space centre cell·S + position, and its turn.
struct FlatPose {
  dvec3 centre;
  dmat3 rotation;
};
FlatPose flat_pose(const tiles::WangSet& set, const Placed& p) {
  const tiles::Instance& in = set.tiles[p.tile].instances[p.instance];
  return {dvec3(p.cell.x * set.edge + in.position.x, p.cell.y * set.edge + in.position.y, in.position.z),
          dmat3(glm::mat3_cast(in.rotation))};
}

// UV islands: triangles that share a UV index lie in one connected piece of the chart.
std::vector<std::uint32_t> uv_islands(const mesh::ProxyMesh& mesh) {
  std::vector<std::uint32_t> parent(mesh.uvs.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (const auto& tri : mesh.uv_triangles) {
    const std::uint32_t root = find(tri[0]);
    for (int c = 1; c < 3; ++c) parent[find(tri[c])] = root;
  }
  std::vector<std::uint32_t> island(mesh.uv_triangles.size());
  for (std::size_t t = 0; t < island.size(); ++t) island[t] = find(mesh.uv_triangles[t][0]);
  return island;
}

struct Segment {
  dvec3 a, b;
};

double point_segment_distance(const dvec3& p, const Segment& s) {
  const dvec3 ab = s.b - s.a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - s.a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (s.a + t * ab));
}

// The UV-seam edges of the mesh as segments (compartment space), from the mapping's edge bits.
std::vector<Segment> seam_segments(const MembraneMapping& mapping) {
  std::vector<Segment> segments;
  for (std::size_t t = 0; t < mapping.triangle_count(); ++t) {
    const TriangleMapping& tm = mapping.triangle(t);
    for (int k = 0; k < 3; ++k)
      if ((tm.seam_edges >> k) & 1u) segments.push_back({dvec3(tm.position[k]), dvec3(tm.position[(k + 1) % 3])});
  }
  return segments;
}

// Copy a relative to copy b, as CollisionShape poses: b's centre is formed as a difference in double
// so compartment coordinates of tens of µm lose nothing to float.
bool atoms_clash(const tiles::CollisionShape& sa, const Placed& a, const tiles::CollisionShape& sb, const Placed& b,
                 float clearance) {
  const tiles::Pose pa{glm::vec3(0.f), a.rotation};
  const tiles::Pose pb{glm::vec3(b.centre - a.centre), b.rotation};
  return tiles::copies_collide(sa, pa, sb, pb, tiles::ClashRule{clearance, {}});
}

// How far any atom of b moves relative to a between the flat tiling and the surface, in a's frame:
// |u| + ‖M‖_F · r_b with u = R_aᵀ(c_b − c_a) − Q_aᵀ(T_b − T_a) and M = R_aᵀR_b − Q_aᵀQ_b.
double relative_displacement(const tiles::WangSet& set, const Placed& a, const Placed& b, double radius_b) {
  const FlatPose fa = flat_pose(set, a), fb = flat_pose(set, b);
  const dmat3 ra(a.rotation), rb(b.rotation);
  const dvec3 u = glm::transpose(ra) * (b.centre - a.centre) - glm::transpose(fa.rotation) * (fb.centre - fa.centre);
  const dmat3 m = glm::transpose(ra) * rb - glm::transpose(fa.rotation) * fb.rotation;
  double f = 0.0;
  for (int c = 0; c < 3; ++c) f += glm::dot(m[c], m[c]);
  return glm::length(u) + std::sqrt(f) * radius_b;
}

std::uint64_t cell_key(const glm::ivec3& c) {
  return (std::uint64_t(std::uint32_t(c.x) & 0x1FFFFF) << 42) | (std::uint64_t(std::uint32_t(c.y) & 0x1FFFFF) << 21) |
         std::uint64_t(std::uint32_t(c.z) & 0x1FFFFF);
}

}  // namespace

std::uint64_t PrunedMembrane::dropped_count() const {
  std::uint64_t n = 0;
  for (const auto& keys : dropped) n += keys.size();
  return n;
}

namespace {

// The molecule types as the pruning tests them, and how far the set's copies reach.
struct TypeShapes {
  std::vector<tiles::CollisionShape> shapes;
  std::vector<double> radius, smallest_atom;
  double highest = 0.0, widest = 0.0;  // largest |z| of an instance and largest type radius
};

TypeShapes type_shapes(const std::vector<tiles::MoleculeType>& types, const tiles::WangSet& set) {
  TypeShapes out;
  for (const tiles::MoleculeType& t : types) {
    out.shapes.emplace_back(t);
    out.radius.push_back(out.shapes.back().radius());
    double r = INFINITY;
    for (const tiles::AtomSphere& a : t.atoms) r = std::min(r, double(a.radius));
    out.smallest_atom.push_back(r);
  }
  for (const tiles::WangTile& tile : set.tiles)
    for (const tiles::Instance& in : tile.instances) {
      out.highest = std::max(out.highest, std::abs(double(in.position.z)));
      out.widest = std::max(out.widest, out.radius[in.type]);
    }
  return out;
}

std::uint64_t count_owned_copies(const MembraneMapping& mapping, const PruningSettings& settings, int threads) {
  if (settings.owned_copies) return *settings.owned_copies;
  std::vector<std::uint64_t> owned(mapping.triangle_count(), 0);
  parallel_for(owned.size(), threads, [&](std::size_t t) {
    mapping.for_each_owned_membrane_place(t, [&](const OwnedPlace&) { ++owned[t]; }, SeamRule::ignore);
  });
  return std::accumulate(owned.begin(), owned.end(), std::uint64_t{0});
}

// Which triangles, and within them which copies, to check. Two copies on the two sides of a seam
// that clash have surface points X, X' with |X − X'| < r + r' + |z| + |z'|, and the seam passes
// between them: each lies within its own r + |z| plus the widest r' + |z'| of the seam. The border
// of the triangles checked whole is such a line too: a copy outside them that could clash with one
// inside lies within that reach of it.
struct CheckedRegion {
  bool whole_surface = false;
  std::vector<char> whole_triangle;  // per triangle: every copy checked
  std::vector<Segment> seams;        // the UV seams and the border of the triangles checked whole
  std::vector<std::vector<std::uint32_t>> near_seams;  // per triangle: the seams its copies may clash across
  double reach_other = 0.0;
};

// The edges between a triangle checked whole and one that is not (position indices decide adjacency).
void add_border_segments(const mesh::ProxyMesh& mesh, const std::vector<char>& whole, std::vector<Segment>& out) {
  for (const mesh::MeshEdge& e : mesh::collect_edges(mesh)) {
    bool in = false, outside = e.uses.size() < 2;
    for (const mesh::EdgeUse& use : e.uses) (whole[use.face] ? in : outside) = true;
    if (in && outside) out.push_back({mesh.positions[e.a], mesh.positions[e.b]});
  }
}

// Segments in a hash grid of cubes at least as wide as the largest distance asked about, so that a
// query looks at the 27 cells around a point only.
class SegmentGrid {
public:
  SegmentGrid(const std::vector<Segment>& segments, double cell) : cell_(std::max(cell, 1.0)) {
    for (std::uint32_t s = 0; s < segments.size(); ++s) {
      const glm::ivec3 lo = cell_of(glm::min(segments[s].a, segments[s].b)), hi = cell_of(glm::max(segments[s].a, segments[s].b));
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) cells_[cell_key({x, y, z})].push_back(s);
    }
  }
  // Segments within `distance` (at most the cell size) of `p`, each once, ascending.
  std::vector<std::uint32_t> near(const std::vector<Segment>& segments, const dvec3& p, double distance) const {
    std::vector<std::uint32_t> found;
    const glm::ivec3 c = cell_of(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(cell_key(c + glm::ivec3(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const std::uint32_t s : it->second)
            if (point_segment_distance(p, segments[s]) < distance) found.push_back(s);
        }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }

private:
  glm::ivec3 cell_of(const dvec3& p) const { return glm::ivec3(glm::floor(p / cell_)); }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

CheckedRegion checked_region(const MembraneMapping& mapping, const mesh::ProxyMesh& mesh, const TypeShapes& t,
                             bool whole_surface, const std::vector<char>& checked_triangles, int threads) {
  const std::size_t triangles = mapping.triangle_count();
  CheckedRegion region{whole_surface, {}, {}, std::vector<std::vector<std::uint32_t>>(triangles), t.widest + t.highest + 2.0};
  if (whole_surface) return region;
  region.whole_triangle = checked_triangles;
  region.whole_triangle.resize(triangles, 0);
  region.seams = seam_segments(mapping);
  add_border_segments(mesh, region.whole_triangle, region.seams);
  std::vector<double> extent(triangles, 0.0);
  std::vector<dvec3> centre(triangles);
  double widest = 0.0;
  for (std::size_t tri = 0; tri < triangles; ++tri) {
    const TriangleMapping& tm = mapping.triangle(tri);
    centre[tri] = (dvec3(tm.position[0]) + dvec3(tm.position[1]) + dvec3(tm.position[2])) / 3.0;
    for (const glm::vec3& p : tm.position) extent[tri] = std::max(extent[tri], glm::length(dvec3(p) - centre[tri]));
    widest = std::max(widest, extent[tri]);
  }
  const double reach = t.widest + t.highest + region.reach_other;
  const SegmentGrid grid(region.seams, widest + reach);
  parallel_for(triangles, threads, [&](std::size_t tri) {
    if (!region.whole_triangle[tri]) region.near_seams[tri] = grid.near(region.seams, centre[tri], extent[tri] + reach);
  });
  return region;
}

void check_key_room(const MembraneMapping& mapping) {
  const std::uint32_t W = static_cast<std::uint32_t>(mapping.replication_area().x);
  std::size_t largest_tile = 0;
  for (const tiles::WangTile& tile : mapping.set().tiles) largest_tile = std::max(largest_tile, tile.instances.size());
  const std::uint64_t slots = std::uint64_t(W) * std::uint64_t(mapping.replication_area().y);
  if (largest_tile > (std::size_t{1} << gpu::NANO_DROP_INSTANCE_BITS) || slots > (std::uint64_t{1} << (32 - gpu::NANO_DROP_INSTANCE_BITS)))
    throw InputError("", "membrane", "a Wang square of " + std::to_string(largest_tile) + " copies or a replication area of " +
                                         std::to_string(slots) + " slots is too large for the dropped-copy keys (2^16 each)");
  // Placed keeps the tile and the instance in 16 bits each.
  static_assert(gpu::NANO_DROP_INSTANCE_BITS <= 16);
  if (mapping.set().tiles.size() > (std::size_t{1} << 16))
    throw InputError("", "membrane", "a Wang set of " + std::to_string(mapping.set().tiles.size()) + " tiles is more than 2^16");
}

Placed placed_copy(const MembraneMapping& mapping, std::size_t t, const OwnedPlace& m, std::uint32_t key,
                   std::uint32_t island) {
  const tiles::Instance& in = mapping.set().tiles[m.tile].instances[m.instance];
  Placed p;
  p.triangle = static_cast<std::uint32_t>(t);
  p.key = key;
  p.type = m.type;
  p.island = island;
  p.cell = m.cell;
  p.tile = static_cast<std::uint16_t>(m.tile);
  p.instance = static_cast<std::uint16_t>(m.instance);
  p.alternate = in.alternate;
  p.has_alternate = in.has_alternate;
  const gpu::Affine3 transform = mapping.transform_of(t, m);
  p.centre = dvec3(transform.translation);
  p.rotation = transform.linear;
  return p;
}

// The owned copies to check, in triangle order, less those dropped before. Two passes (which copies
// of each triangle, then placing them at their offsets) so that the copies of a whole cell are
// never held twice.
std::vector<Placed> copies_to_check(const MembraneMapping& mapping, const mesh::ProxyMesh& mesh, const TypeShapes& t,
                                    const CheckedRegion& region, const PruningSettings& settings, int threads) {
  const std::size_t triangles = mapping.triangle_count();
  const std::vector<std::uint32_t> island = uv_islands(mesh);
  // Calls take(place, key) for each copy of `tri` to check.
  const auto for_each_checked = [&](std::size_t tri, const auto& take) {
    const bool whole = region.whole_surface || region.whole_triangle[tri];
    if (!whole && region.near_seams[tri].empty()) return;
    const TriangleMapping& tm = mapping.triangle(tri);
    const std::vector<std::uint32_t>& near_seams = region.near_seams[tri];
    mapping.for_each_owned_membrane_place(
        tri,
        [&](const OwnedPlace& m) {
          const std::uint32_t key = mapping.copy_key(tri, m);
          if (!settings.dropped_before.empty() &&
              std::binary_search(settings.dropped_before[tri].begin(), settings.dropped_before[tri].end(), key))
            return;
          if (!whole) {
            const tiles::Instance& in = mapping.set().tiles[m.tile].instances[m.instance];
            const dvec3 surface(gpu::chart_position(tm.chart, m.uv));
            const double reach = t.radius[m.type] + std::abs(double(in.position.z)) + region.reach_other;
            const auto near = [&](std::uint32_t s) { return point_segment_distance(surface, region.seams[s]) < reach; };
            if (std::none_of(near_seams.begin(), near_seams.end(), near)) return;
          }
          take(m, key);
        },
        SeamRule::ignore);
  };
  std::vector<std::size_t> offset(triangles + 1, 0);
  parallel_for(triangles, threads, [&](std::size_t tri) {
    for_each_checked(tri, [&](const OwnedPlace&, std::uint32_t) { ++offset[tri + 1]; });
  });
  for (std::size_t tri = 0; tri < triangles; ++tri) offset[tri + 1] += offset[tri];
  std::vector<Placed> copies(offset[triangles]);
  parallel_for(triangles, threads, [&](std::size_t tri) {
    std::size_t next = offset[tri];
    for_each_checked(tri, [&](const OwnedPlace& m, std::uint32_t key) {
      copies[next++] = placed_copy(mapping, tri, m, key, island[tri]);
    });
  });
  return copies;
}

// Small copies (lipids and the like) in a hash grid of cells twice their largest radius; the few
// large ones (proteins) look through the grid within their own reach and at each other directly.
struct CopyGrid {
  double small_limit = 0.0, small_max = 0.0, cell = 1.0;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  std::vector<std::uint32_t> large;

  glm::ivec3 cell_of(const dvec3& c) const { return glm::ivec3(glm::floor(c / cell)); }
  const std::vector<std::uint32_t>* at(const glm::ivec3& c) const {
    const auto it = cells.find(cell_key(c));
    return it == cells.end() ? nullptr : &it->second;
  }
};

CopyGrid grid_copies(const std::vector<Placed>& copies, const std::vector<double>& radius) {
  CopyGrid grid;
  std::vector<double> sorted_radii;
  for (const Placed& p : copies) sorted_radii.push_back(radius[p.type]);
  std::nth_element(sorted_radii.begin(), sorted_radii.begin() + sorted_radii.size() / 2, sorted_radii.end());
  grid.small_limit = 1.5 * sorted_radii[sorted_radii.size() / 2];
  for (const Placed& p : copies)
    if (radius[p.type] <= grid.small_limit) grid.small_max = std::max(grid.small_max, radius[p.type]);
  grid.cell = std::max(2.0 * grid.small_max, 1.0);
  for (std::uint32_t i = 0; i < copies.size(); ++i) {
    if (radius[copies[i].type] <= grid.small_limit) grid.cells[cell_key(grid.cell_of(copies[i].centre))].push_back(i);
    else grid.large.push_back(i);
  }
  return grid;
}

struct Found {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> clashes;
  std::uint64_t candidates = 0, atom_tests = 0;
};

// Tests a pair of copies for a clash: bounding spheres first, then (unless the flat tiling vouches
// for the pair) their atoms.
struct PairTest {
  const std::vector<Placed>& copies;
  const TypeShapes& types;
  const PruningSettings& settings;
  std::vector<char> always_tested;  // per type
  const tiles::WangSet& set;

  void operator()(std::uint32_t i, std::uint32_t j, Found& f) const {
    const Placed& a = copies[i];
    const Placed& b = copies[j];
    const std::vector<double>& radius = types.radius;
    const double reach = radius[a.type] + radius[b.type];
    const dvec3 between = b.centre - a.centre;
    if (glm::dot(between, between) >= reach * reach) return;
    ++f.candidates;
    if (a.island == b.island && settings.flat_clearance > settings.clearance && !always_tested[a.type] &&
        !always_tested[b.type] && !a.alternate && !b.alternate) {
      const double slack =
          (double(settings.flat_clearance) - settings.clearance) * (types.smallest_atom[a.type] + types.smallest_atom[b.type]);
      if (relative_displacement(set, a, b, radius[b.type]) < slack) return;
    }
    ++f.atom_tests;
    if (atoms_clash(types.shapes[a.type], a, types.shapes[b.type], b, settings.clearance)) f.clashes.emplace_back(i, j);
  }
};

// Every clashing pair, found in chunks of small copies on the jobs plus one last entry for the large ones.
std::vector<Found> find_clashes(const std::vector<Placed>& copies, const CopyGrid& grid, const PairTest& test, int threads) {
  constexpr std::size_t kChunk = 2048;
  const std::vector<double>& radius = test.types.radius;
  const std::size_t chunks = (copies.size() + kChunk - 1) / kChunk;
  std::vector<Found> found(chunks + 1);
  parallel_for(chunks, threads, [&](std::size_t chunk) {
    Found& f = found[chunk];
    for (std::size_t i = chunk * kChunk; i < std::min(copies.size(), (chunk + 1) * kChunk); ++i) {
      if (radius[copies[i].type] > grid.small_limit) continue;
      const glm::ivec3 c = grid.cell_of(copies[i].centre);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (const std::vector<std::uint32_t>* cell = grid.at(c + glm::ivec3(dx, dy, dz)))
              for (const std::uint32_t j : *cell)
                if (j > i) test(std::uint32_t(i), j, f);
    }
  });
  Found& f = found[chunks];
  for (std::size_t k = 0; k < grid.large.size(); ++k) {
    const std::uint32_t i = grid.large[k];
    for (std::size_t l = k + 1; l < grid.large.size(); ++l) test(i, grid.large[l], f);
    const int span = static_cast<int>(std::ceil((radius[copies[i].type] + grid.small_max) / grid.cell));
    const glm::ivec3 c = grid.cell_of(copies[i].centre);
    for (int dz = -span; dz <= span; ++dz)
      for (int dy = -span; dy <= span; ++dy)
        for (int dx = -span; dx <= span; ++dx)
          if (const std::vector<std::uint32_t>* cell = grid.at(c + glm::ivec3(dx, dy, dz)))
            for (const std::uint32_t j : *cell) test(i, j, f);
  }
  return found;
}

// Per copy, the copies it clashes with; the counts go to `out`.
std::vector<std::vector<std::uint32_t>> conflict_lists(const std::vector<Found>& found, std::size_t copies,
                                                       PrunedMembrane& out) {
  std::vector<std::vector<std::uint32_t>> conflicts(copies);
  for (const Found& f : found) {
    out.candidate_pairs += f.candidates;
    out.atom_tests += f.atom_tests;
    out.clashing_pairs += f.clashes.size();
    for (const auto& [i, j] : f.clashes) {
      conflicts[i].push_back(j);
      conflicts[j].push_back(i);
    }
  }
  return conflicts;
}

// Greedy independent set: proteins (larger radius) first, then the copies of the set proper (those
// without an alternate before those with one, which lose less when dropped), then the alternates
// (each only where what it stands in for was dropped), each group the copies with fewer clashes
// first. An alternate without a clash is shown: its original was dropped before.
std::vector<char> kept_copies(const std::vector<Placed>& copies, const std::vector<std::vector<std::uint32_t>>& conflicts,
                              const std::vector<double>& radius, double small_limit) {
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < copies.size(); ++i)
    if (!conflicts[i].empty()) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const bool large_a = radius[copies[a].type] > small_limit, large_b = radius[copies[b].type] > small_limit;
    if (large_a != large_b) return large_a;
    if (!large_a && copies[a].alternate != copies[b].alternate) return copies[b].alternate;
    if (!large_a && copies[a].has_alternate != copies[b].has_alternate) return copies[b].has_alternate;
    if (radius[copies[a].type] != radius[copies[b].type]) return radius[copies[a].type] > radius[copies[b].type];
    if (conflicts[a].size() != conflicts[b].size()) return conflicts[a].size() < conflicts[b].size();
    return a < b;
  });
  std::vector<char> kept(copies.size(), 1), decided(copies.size(), 0);
  for (const std::uint32_t i : order) {
    decided[i] = 1;
    for (const std::uint32_t j : conflicts[i])
      if (decided[j] && kept[j]) {
        kept[i] = 0;
        break;
      }
  }
  return kept;
}

// A dropped copy and a shown alternate are both listed with the drops.
void record_drops(const std::vector<Placed>& copies, const std::vector<char>& kept, PrunedMembrane& out) {
  for (std::uint32_t i = 0; i < copies.size(); ++i)
    if (copies[i].alternate && kept[i]) {
      out.dropped[copies[i].triangle].push_back(copies[i].key);
      ++out.alternates_by_type[copies[i].type];
    } else if (!copies[i].alternate && !kept[i]) {
      out.dropped[copies[i].triangle].push_back(copies[i].key);
      ++out.dropped_by_type[copies[i].type];
    }
  for (auto& keys : out.dropped) std::sort(keys.begin(), keys.end());
}

}  // namespace

PrunedMembrane prune_membrane(const MembraneMapping& mapping, const mesh::ProxyMesh& mesh,
                              const std::vector<tiles::MoleculeType>& types, const PruningSettings& settings,
                              int threads) {
  const std::size_t triangles = mapping.triangle_count();
  PrunedMembrane out;
  out.dropped.assign(triangles, {});
  out.dropped_by_type.assign(types.size(), 0);
  out.alternates_by_type.assign(types.size(), 0);
  if (triangles == 0 || types.empty()) return out;

  const TypeShapes shapes = type_shapes(types, mapping.set());
  out.owned_copies = count_owned_copies(mapping, settings, threads);
  out.whole_surface = settings.whole_surface || out.owned_copies <= settings.whole_surface_budget;
  const CheckedRegion region = checked_region(mapping, mesh, shapes, out.whole_surface, settings.checked_triangles, threads);
  out.checked_triangles = out.whole_surface ? triangles
                                            : std::uint64_t(std::count(region.whole_triangle.begin(), region.whole_triangle.end(), 1));
  check_key_room(mapping);
  const std::vector<Placed> copies = copies_to_check(mapping, mesh, shapes, region, settings, threads);
  out.checked_copies = copies.size();
  if (!settings.dropped_before.empty()) out.dropped = settings.dropped_before;
  if (copies.empty()) return out;

  PairTest test{copies, shapes, settings, std::vector<char>(types.size(), 0), mapping.set()};
  for (const std::uint32_t type : settings.always_tested)
    if (type < types.size()) test.always_tested[type] = 1;
  const CopyGrid grid = grid_copies(copies, shapes.radius);
  const std::vector<std::vector<std::uint32_t>> conflicts =
      conflict_lists(find_clashes(copies, grid, test, threads), copies.size(), out);
  record_drops(copies, kept_copies(copies, conflicts, shapes.radius, grid.small_limit), out);
  return out;
}

std::uint64_t limit_copies(const MembraneMapping& mapping, PrunedMembrane& pruned, std::uint32_t type, std::uint64_t count,
                           std::vector<std::uint32_t>* kept_on) {
  struct Copy {
    std::uint32_t triangle, key;
    dvec3 centre;
  };
  std::vector<Copy> copies;
  for (std::size_t t = 0; t < mapping.triangle_count(); ++t) {
    const std::vector<std::uint32_t>& dropped = pruned.dropped[t];
    mapping.for_each_owned_membrane_place(
        t,
        [&](const OwnedPlace& m) {
          if (m.type != type || mapping.set().tiles[m.tile].instances[m.instance].alternate) return;
          const std::uint32_t key = mapping.copy_key(t, m);
          if (std::binary_search(dropped.begin(), dropped.end(), key)) return;
          copies.push_back({static_cast<std::uint32_t>(t), key, dvec3(mapping.centre_of(t, m))});
        },
        SeamRule::ignore);
  }
  if (copies.size() <= count) {
    if (kept_on)
      for (const Copy& c : copies) kept_on->push_back(c.triangle);
    return copies.size();
  }
  std::vector<double> nearest(copies.size(), INFINITY);
  std::vector<char> kept(copies.size(), 0);
  std::size_t next = 0;
  for (std::uint64_t k = 0; k < count; ++k) {
    kept[next] = 1;
    std::size_t farthest = 0;
    double best = -1.0;
    for (std::size_t i = 0; i < copies.size(); ++i) {
      nearest[i] = std::min(nearest[i], glm::length(copies[i].centre - copies[next].centre));
      if (!kept[i] && nearest[i] > best) {
        best = nearest[i];
        farthest = i;
      }
    }
    next = farthest;
  }
  for (std::size_t i = 0; i < copies.size(); ++i)
    if (kept[i] && kept_on) kept_on->push_back(copies[i].triangle);
  for (std::size_t i = 0; i < copies.size(); ++i)
    if (!kept[i]) {
      std::vector<std::uint32_t>& keys = pruned.dropped[copies[i].triangle];
      keys.insert(std::upper_bound(keys.begin(), keys.end(), copies[i].key), copies[i].key);
      ++pruned.dropped_by_type[type];
    }
  return count;
}

}  // namespace nano::shell
