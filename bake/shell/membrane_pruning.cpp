#include "bake/shell/membrane_pruning.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include <glm/gtc/quaternion.hpp>

#include "bake/mesh/mesh_edges.hpp"
#include "bake/tiles/collision_shape.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"
#include "shared/render_membrane_filter.h"

namespace nano::shell {
namespace {

using glm::dvec3;

// One owned copy where the triangle places it. A whole 1 µm cell checks 10^7 of them at once, so
// what the Wang tile instance says (its flat pose) is looked up, not kept: 96 bytes a copy.
struct Placed {
  dvec3 centre{0.0};         // compartment space, in double: far-off cells lose nothing to float
  glm::mat3 rotation{1.f};   // the atom test's own precision
  std::uint32_t triangle = 0;
  std::uint32_t key = 0;     // membrane_copy_key(slot, instance)
  std::uint32_t type = 0;
  bool has_alternate = false;  // tiles::Instance::has_alternate: dropped before a copy without one
};
static_assert(sizeof(Placed) <= 96);

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
  std::vector<double> radius;
  double highest = 0.0, widest = 0.0;  // largest |z| of an instance and largest type radius
};

TypeShapes type_shapes(const std::vector<tiles::MoleculeType>& types, const tiles::WangSet& set) {
  TypeShapes out;
  for (const tiles::MoleculeType& t : types) {
    out.shapes.emplace_back(t);
    out.radius.push_back(out.shapes.back().radius());
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

Placed placed_copy(const MembraneMapping& mapping, std::size_t t, const OwnedPlace& m, std::uint32_t key) {
  const tiles::Instance& in = mapping.set().tiles[m.tile].instances[m.instance];
  Placed p;
  p.triangle = static_cast<std::uint32_t>(t);
  p.key = key;
  p.type = m.type;
  p.has_alternate = in.has_alternate;
  const gpu::Affine3 transform = mapping.transform_of(t, m);
  p.centre = dvec3(transform.translation);
  p.rotation = transform.linear;
  return p;
}

// Calls take(place, key) for each copy of triangle `tri` to check, less those dropped before: the
// set's own copies, or its alternates.
template <class Take>
void for_each_checked(const MembraneMapping& mapping, const TypeShapes& t, const CheckedRegion& region,
                      const PruningSettings& settings, bool alternates, std::size_t tri, const Take& take) {
  const bool whole = region.whole_surface || region.whole_triangle[tri];
  if (!whole && region.near_seams[tri].empty()) return;
  const TriangleMapping& tm = mapping.triangle(tri);
  const std::vector<std::uint32_t>& near_seams = region.near_seams[tri];
  mapping.for_each_owned_membrane_place(
      tri,
      [&](const OwnedPlace& m) {
        const tiles::Instance& in = mapping.set().tiles[m.tile].instances[m.instance];
        const std::uint32_t key = mapping.copy_key(tri, m);
        if (!settings.dropped_before.empty() &&
            std::binary_search(settings.dropped_before[tri].begin(), settings.dropped_before[tri].end(), key))
          return;
        if (!whole) {
          const dvec3 surface(gpu::chart_position(tm.chart, m.uv));
          const double reach = t.radius[m.type] + std::abs(double(in.position.z)) + region.reach_other;
          const auto near = [&](std::uint32_t s) { return point_segment_distance(surface, region.seams[s]) < reach; };
          if (std::none_of(near_seams.begin(), near_seams.end(), near)) return;
        }
        take(m, key);
      },
      SeamRule::ignore, alternates ? Instances::alternates : Instances::originals);
}

// The set's own copies to check, in triangle order. Two passes (which copies of each triangle, then
// placing them at their offsets) so that the copies of a whole cell are never held twice.
std::vector<Placed> copies_to_check(const MembraneMapping& mapping, const TypeShapes& t, const CheckedRegion& region,
                                    const PruningSettings& settings, int threads) {
  const std::size_t triangles = mapping.triangle_count();
  std::vector<std::size_t> offset(triangles + 1, 0);
  parallel_for(triangles, threads, [&](std::size_t tri) {
    for_each_checked(mapping, t, region, settings, false, tri, [&](const OwnedPlace&, std::uint32_t) { ++offset[tri + 1]; });
  });
  for (std::size_t tri = 0; tri < triangles; ++tri) offset[tri + 1] += offset[tri];
  std::vector<Placed> copies(offset[triangles]);
  parallel_for(triangles, threads, [&](std::size_t tri) {
    std::size_t next = offset[tri];
    for_each_checked(mapping, t, region, settings, false, tri, [&](const OwnedPlace& m, std::uint32_t key) {
      copies[next++] = placed_copy(mapping, tri, m, key);
    });
  });
  return copies;
}

// The set's alternates for which wanted(placed) holds, in triangle order. Alternates outnumber the
// set's own copies (each lipid put aside five ways) and few are wanted: only those are held.
template <class Wanted>
std::vector<Placed> alternates_to_check(const MembraneMapping& mapping, const TypeShapes& t, const CheckedRegion& region,
                                        const PruningSettings& settings, const Wanted& wanted, int threads) {
  std::vector<std::vector<Placed>> per_triangle(mapping.triangle_count());
  parallel_for(per_triangle.size(), threads, [&](std::size_t tri) {
    for_each_checked(mapping, t, region, settings, true, tri, [&](const OwnedPlace& m, std::uint32_t key) {
      const Placed p = placed_copy(mapping, tri, m, key);
      if (wanted(p)) per_triangle[tri].push_back(p);
    });
  });
  std::vector<Placed> out;
  for (std::vector<Placed>& list : per_triangle) out.insert(out.end(), list.begin(), list.end());
  return out;
}

// Copies larger than this (1.5 x the median radius: proteins among lipids) are tested copy against
// copy rather than atom by atom, and go first in the independent set.
double small_copy_limit(const std::vector<Placed>& copies, const std::vector<double>& radius) {
  std::vector<double> radii;
  radii.reserve(copies.size());
  for (const Placed& p : copies) radii.push_back(radius[p.type]);
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return 1.5 * radii[radii.size() / 2];
}

// Copy a relative to copy b, as CollisionShape poses: b's centre is formed as a difference in double
// so compartment coordinates of tens of µm lose nothing to float.
bool copies_clash(const TypeShapes& types, const Placed& a, const Placed& b, float clearance) {
  const tiles::Pose pa{glm::vec3(0.f), a.rotation};
  const tiles::Pose pb{glm::vec3(b.centre - a.centre), b.rotation};
  return tiles::copies_collide(types.shapes[a.type], pa, types.shapes[b.type], pb, tiles::ClashRule{clearance, {}});
}

using CopyPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Every pair of copies with atoms closer than clearance · (r1 + r2). Among the small copies (a
// bilayer's lipids: many copies, each meeting ~40 neighbours) it is found atom by atom: space is cut
// into cubic chunks; a chunk takes the atoms within reach of it from the small copies whose spheres
// come that near, bins them in cells one reach wide and measures each atom against the atoms of
// other copies in the half of the 27 cells around it that follows its own. A copy's atoms are placed
// once per chunk its sphere meets (about twice), where a test of each pair of copies placed them once
// per neighbour. An atom belongs to the chunk its compartment-space centre falls in; a pair is kept
// by the chunks owning either atom (duplicates go in the final sort). A pair with a large copy (a
// protein: few copies, each mostly atoms no neighbour comes near) is tested copy against copy
// (tiles::copies_collide passes over the blocks of atoms out of reach).
class ClashSearch {
public:
  ClashSearch(const std::vector<Placed>& copies, const TypeShapes& types, double small_limit, float clearance)
      : copies_(copies), types_(types), clearance_(clearance), small_limit_(small_limit) {
    double largest_small_atom = 0.0;
    for (const Placed& p : copies)
      if (types.radius[p.type] <= small_limit) {
        small_max_ = std::max(small_max_, types.radius[p.type]);
        largest_small_atom = std::max(largest_small_atom, double(types.shapes[p.type].max_atom_radius()));
      }
    reach_ = std::max(2.0 * clearance * largest_small_atom, 1e-3);
    // A small copy that reaches a chunk has its centre in one of the 27 around it.
    chunk_ = std::max(6.0 * (small_max_ + reach_), 16.0 * reach_);
    cell_ = std::max(reach_, (chunk_ + 2.0 * reach_) / 256.0);
    index_copies();
  }

  std::size_t chunk_count() const { return chunks_.size(); }
  const std::vector<std::uint32_t>& large() const { return large_; }

  // The clashing pairs (i < j) of small copies with an atom chunk `c` owns; `measured` counts the
  // atom pairs of two copies whose distance was taken.
  void search_chunk(std::size_t c, CopyPairs& clashes, std::uint64_t& measured) const {
    const glm::ivec3 chunk = chunks_[c];
    const ChunkAtoms atoms = gather(chunk);
    // Most chunks around a membrane own nothing (they hold the reach of their neighbours' copies only);
    // a chunk that owns atoms bins them over the box they fill, not over the whole chunk.
    if (std::find(atoms.owned.begin(), atoms.owned.end(), 1) == atoms.owned.end()) return;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : atoms.position) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float per_cell = static_cast<float>(1.0 / cell_);
    const glm::ivec3 n = glm::ivec3((hi - lo) * per_cell) + 1;
    const auto cell_of = [&](const glm::vec3& p) { return glm::min(glm::ivec3((p - lo) * per_cell), n - 1); };
    const auto index = [&](int x, int y, int z) { return std::uint32_t((z * n.y + y) * n.x + x); };
    // Atoms sorted by cell, x fastest: the cells x-1..x+1 of a row hold one run of atoms.
    const std::size_t count = atoms.position.size();
    std::vector<std::uint32_t> start(std::size_t(n.x) * n.y * n.z + 1, 0), cell(count), order(count);
    for (std::size_t i = 0; i < count; ++i) {
      const glm::ivec3 g = cell_of(atoms.position[i]);
      ++start[(cell[i] = index(g.x, g.y, g.z)) + 1];
    }
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < count; ++i) order[fill[cell[i]]++] = i;
    const ChunkAtoms sorted = atoms.permuted(order);
    std::uint64_t pairs = 0;
    std::unordered_set<std::uint64_t> found;  // a pair of copies once, not once per pair of their atoms
    // Atoms i and j (j after i in the run) of two copies, kept when the chunk owns either.
    const auto measure = [&](std::uint32_t i, std::uint32_t j) {
      if (sorted.copy[i] == sorted.copy[j] || !(sorted.owned[i] | sorted.owned[j])) return;
      ++pairs;
      const float limit = clearance_ * (sorted.radius[i] + sorted.radius[j]);
      const glm::vec3 d = sorted.position[i] - sorted.position[j];
      if (glm::dot(d, d) < limit * limit)
        found.insert(std::uint64_t(std::min(sorted.copy[i], sorted.copy[j])) << 32 | std::max(sorted.copy[i], sorted.copy[j]));
    };
    for (std::uint32_t i = 0; i < count; ++i) {
      const glm::ivec3 g = cell_of(sorted.position[i]);
      const int x0 = std::max(g.x - 1, 0), x1 = std::min(g.x + 1, n.x - 1);
      // The half of the neighbourhood after the atom: the rest of its own cell and the next one in x,
      // the next row (y + 1), the next plane (z + 1).
      for (std::uint32_t j = i + 1; j < start[index(std::min(g.x + 1, n.x - 1), g.y, g.z) + 1]; ++j) measure(i, j);
      if (g.y + 1 < n.y)
        for (std::uint32_t j = start[index(x0, g.y + 1, g.z)]; j < start[index(x1, g.y + 1, g.z) + 1]; ++j) measure(i, j);
      if (g.z + 1 < n.z)
        for (int y = std::max(g.y - 1, 0); y <= std::min(g.y + 1, n.y - 1); ++y)
          for (std::uint32_t j = start[index(x0, y, g.z + 1)]; j < start[index(x1, y, g.z + 1) + 1]; ++j) measure(i, j);
    }
    // Alternates put aside 1 Å overlap their neighbours' alternates in nearly every atom.
    for (const std::uint64_t pair : found) clashes.emplace_back(std::uint32_t(pair >> 32), std::uint32_t(pair));
    measured += pairs;
  }

  // The clashing pairs of large copy large()[k] with the small copies and the later large ones;
  // `tested` counts the pairs of copies tested whole.
  void search_large(std::size_t k, CopyPairs& clashes, std::uint64_t& tested) const {
    const std::uint32_t i = large_[k];
    const Placed& a = copies_[i];
    const double r = types_.radius[a.type];
    const auto test = [&](std::uint32_t j) {
      const Placed& b = copies_[j];
      const double reach = r + types_.radius[b.type];
      const dvec3 between = b.centre - a.centre;
      if (glm::dot(between, between) >= reach * reach) return;
      ++tested;
      if (copies_clash(types_, a, b, clearance_)) clashes.emplace_back(std::min(i, j), std::max(i, j));
    };
    for (std::size_t l = k + 1; l < large_.size(); ++l) test(large_[l]);
    const glm::ivec3 lo = chunk_of(a.centre - (r + small_max_)), hi = chunk_of(a.centre + (r + small_max_));
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
          if (const auto run = runs_.find(cell_key({x, y, z})); run != runs_.end())
            for (std::size_t s = run->second.first; s < run->second.second; ++s) test(small_[s]);
  }

private:
  // The atoms a chunk takes, as columns: place from the chunk's corner, radius, copy, owned by the chunk.
  struct ChunkAtoms {
    std::vector<glm::vec3> position;
    std::vector<float> radius;
    std::vector<std::uint32_t> copy;
    std::vector<char> owned;

    ChunkAtoms permuted(const std::vector<std::uint32_t>& order) const {
      ChunkAtoms out;
      out.position.reserve(order.size()), out.radius.reserve(order.size());
      out.copy.reserve(order.size()), out.owned.reserve(order.size());
      for (const std::uint32_t i : order)
        out.position.push_back(position[i]), out.radius.push_back(radius[i]), out.copy.push_back(copy[i]),
            out.owned.push_back(owned[i]);
      return out;
    }
  };

  // Float rounding of an atom's place relative to a chunk stays far below this (Å).
  static constexpr float kFaceHair = 1e-2f;

  glm::ivec3 chunk_of(const dvec3& p) const { return glm::ivec3(glm::floor(p / chunk_)); }

  // Small copies sorted by the chunk of their centre, each chunk's run found by its key; the large
  // ones listed apart; the chunks that may own an atom (those around a chunk holding a small copy).
  void index_copies() {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
    for (std::uint32_t i = 0; i < copies_.size(); ++i)
      if (types_.radius[copies_[i].type] <= small_limit_) keyed.emplace_back(cell_key(chunk_of(copies_[i].centre)), i);
      else large_.push_back(i);
    std::sort(keyed.begin(), keyed.end());
    small_.resize(keyed.size());
    for (std::size_t k = 0; k < keyed.size(); ++k) {
      small_[k] = keyed[k].second;
      auto [it, first] = runs_.try_emplace(keyed[k].first, k, k + 1);
      if (!first) {
        it->second.second = k + 1;
        continue;
      }
      const glm::ivec3 c = chunk_of(copies_[keyed[k].second].centre);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) chunks_.push_back(c + glm::ivec3(dx, dy, dz));
    }
    const auto less = [](const glm::ivec3& a, const glm::ivec3& b) {
      return a.z != b.z ? a.z < b.z : a.y != b.y ? a.y < b.y : a.x < b.x;
    };
    std::sort(chunks_.begin(), chunks_.end(), less);
    chunks_.erase(std::unique(chunks_.begin(), chunks_.end()), chunks_.end());
  }

  // The atoms within reach of the chunk, of every small copy whose sphere comes that near.
  ChunkAtoms gather(const glm::ivec3& chunk) const {
    const dvec3 origin = dvec3(chunk) * chunk_;
    const float extent = static_cast<float>(chunk_), margin = static_cast<float>(reach_) + kFaceHair;
    ChunkAtoms atoms;
    const auto take = [&](std::uint32_t i) {
      const Placed& p = copies_[i];
      const double r = types_.radius[p.type];
      const dvec3 gap = glm::max(glm::max(origin - p.centre, p.centre - (origin + chunk_)), dvec3(0.0));
      if (glm::dot(gap, gap) >= (r + reach_) * (r + reach_)) return;
      const glm::vec3 centre(p.centre - origin);
      for (const tiles::AtomSphere& a : types_.shapes[p.type].atoms()) {
        const glm::vec3 offset = p.rotation * a.centre;
        const glm::vec3 local = centre + offset;
        if (glm::any(glm::lessThan(local, glm::vec3(-margin))) || glm::any(glm::greaterThan(local, glm::vec3(extent + margin))))
          continue;
        // Within a hair of a face, float rounding differs from chunk to chunk: decide in double.
        const glm::vec3 face = glm::min(glm::abs(local), glm::abs(local - extent));
        const bool owned = std::min({face.x, face.y, face.z}) > kFaceHair
                               ? glm::all(glm::greaterThanEqual(local, glm::vec3(0.f))) && glm::all(glm::lessThan(local, glm::vec3(extent)))
                               : chunk_of(p.centre + dvec3(offset)) == chunk;
        atoms.position.push_back(local), atoms.radius.push_back(a.radius), atoms.copy.push_back(i), atoms.owned.push_back(owned);
      }
    };
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (const auto run = runs_.find(cell_key(chunk + glm::ivec3(dx, dy, dz))); run != runs_.end())
            for (std::size_t k = run->second.first; k < run->second.second; ++k) take(small_[k]);
    return atoms;
  }

  const std::vector<Placed>& copies_;
  const TypeShapes& types_;
  float clearance_;
  double small_limit_, small_max_ = 0.0, reach_ = 0.0, chunk_ = 1.0, cell_ = 1.0;
  std::vector<std::uint32_t> small_, large_;
  std::unordered_map<std::uint64_t, std::pair<std::size_t, std::size_t>> runs_;
  std::vector<glm::ivec3> chunks_;
};

struct Found {
  CopyPairs clashes;
  std::uint64_t atom_pairs = 0, copy_pairs = 0;
};

// Every clashing pair once, ascending, whatever the threads: the chunks' and the large copies'.
Found find_clashes(const ClashSearch& search, int threads) {
  const std::size_t chunks = search.chunk_count();
  std::vector<Found> parts(chunks + search.large().size());
  parallel_for(parts.size(), threads, [&](std::size_t k) {
    if (k < chunks) search.search_chunk(k, parts[k].clashes, parts[k].atom_pairs);
    else search.search_large(k - chunks, parts[k].clashes, parts[k].copy_pairs);
  });
  Found all;
  for (Found& f : parts) {
    all.atom_pairs += f.atom_pairs;
    all.copy_pairs += f.copy_pairs;
    all.clashes.insert(all.clashes.end(), f.clashes.begin(), f.clashes.end());
  }
  std::sort(all.clashes.begin(), all.clashes.end());
  all.clashes.erase(std::unique(all.clashes.begin(), all.clashes.end()), all.clashes.end());
  return all;
}

// Per copy, the copies it clashes with; the counts go to `out`.
std::vector<std::vector<std::uint32_t>> conflict_lists(const Found& found, std::size_t copies, PrunedMembrane& out) {
  std::vector<std::vector<std::uint32_t>> conflicts(copies);
  out.atom_pairs += found.atom_pairs;
  out.copy_pairs_tested += found.copy_pairs;
  out.clashing_pairs += found.clashes.size();
  for (const auto& [i, j] : found.clashes) {
    conflicts[i].push_back(j);
    conflicts[j].push_back(i);
  }
  return conflicts;
}

}  // namespace

void swap_one_for_two(const std::vector<std::vector<std::uint32_t>>& conflicts, const std::vector<char>& swappable,
                      std::vector<char>& kept) {
  const auto clash = [&](std::uint32_t a, std::uint32_t b) {  // conflict lists are ascending
    return std::binary_search(conflicts[a].begin(), conflicts[a].end(), b);
  };
  std::vector<std::uint32_t> kept_around(conflicts.size(), 0);  // per dropped copy: the kept copies it clashes with
  for (std::uint32_t i = 0; i < conflicts.size(); ++i)
    if (!kept[i])
      for (const std::uint32_t j : conflicts[i]) kept_around[i] += kept[j] ? 1u : 0u;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint32_t c = 0; c < conflicts.size(); ++c) {
      if (!kept[c] || !swappable[c]) continue;
      std::vector<std::uint32_t> taking;
      bool needed = false;  // c alone holds out a copy that may not come back
      for (const std::uint32_t d : conflicts[c]) {
        if (kept[d] || kept_around[d] != 1) continue;
        needed = needed || !swappable[d];
        if (swappable[d] && std::none_of(taking.begin(), taking.end(), [&](std::uint32_t t) { return clash(d, t); }))
          taking.push_back(d);
      }
      if (needed || taking.size() < 2) continue;
      kept[c] = 0;
      for (const std::uint32_t j : conflicts[c]) --kept_around[j];  // c's neighbours were all dropped
      for (const std::uint32_t d : taking) {
        kept[d] = 1;
        for (const std::uint32_t j : conflicts[d]) ++kept_around[j];
      }
      changed = true;
    }
  }
}

namespace {

// Independent set of the set's own copies: greedy, proteins (larger radius) first, then the lipids
// (those without an alternate before those with one, which lose less when dropped), each group the
// copies with fewer clashes first; then swap_one_for_two among the lipids (along a UV seam, where two
// unrelated tilings meet, the greedy order often keeps the one copy that overlaps two).
std::vector<char> kept_copies(const std::vector<Placed>& copies, const std::vector<std::vector<std::uint32_t>>& conflicts,
                              const std::vector<double>& radius, double small_limit) {
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < copies.size(); ++i)
    if (!conflicts[i].empty()) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const bool large_a = radius[copies[a].type] > small_limit, large_b = radius[copies[b].type] > small_limit;
    if (large_a != large_b) return large_a;
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
  std::vector<char> lipid(copies.size());
  for (std::uint32_t i = 0; i < copies.size(); ++i) lipid[i] = radius[copies[i].type] <= small_limit;
  swap_one_for_two(conflicts, lipid, kept);
  return kept;
}

// A dropped copy is listed with the drops.
void record_drops(const std::vector<Placed>& copies, const std::vector<char>& kept, PrunedMembrane& out) {
  for (std::uint32_t i = 0; i < copies.size(); ++i)
    if (!kept[i]) {
      out.dropped[copies[i].triangle].push_back(copies[i].key);
      ++out.dropped_by_type[copies[i].type];
    }
}

// Copies binned in cubic cells, for "which stand within d of this point" with d up to the cell.
class CopyGrid {
public:
  CopyGrid(const std::vector<Placed>& copies, double cell) : copies_(copies), cell_(std::max(cell, 1e-3)) {}
  void add(std::uint32_t i) { cells_[cell_key(cell_of(copies_[i].centre))].push_back(i); }
  template <class Visit>
  void around(const dvec3& p, const Visit& visit) const {
    const glm::ivec3 c = cell_of(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (const auto found = cells_.find(cell_key(c + glm::ivec3(dx, dy, dz))); found != cells_.end())
            for (const std::uint32_t i : found->second) visit(i);
  }

private:
  glm::ivec3 cell_of(const dvec3& p) const { return glm::ivec3(glm::floor(p / cell_)); }
  const std::vector<Placed>& copies_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

// Two copies of one molecule type whose centres stand closer than this (Å) hold one place twice. A
// displaced alternate (its original turned or shifted a few Å, bake/tiles/wang_sets.cpp) may clear
// the clash rule beside its kept original; it must still never be shown there.
constexpr double kSamePlace = 6.0;

// Copies by place: whether one of a given type holds a place (kSamePlace).
class PlaceIndex {
public:
  explicit PlaceIndex(const std::vector<Placed>& copies) : copies_(copies), grid_(copies, kSamePlace) {}
  void add(std::uint32_t i) { grid_.add(i); }
  bool taken(const Placed& a) const {
    bool found = false;
    grid_.around(a.centre, [&](std::uint32_t k) {
      found = found || (copies_[k].type == a.type && glm::length(copies_[k].centre - a.centre) < kSamePlace);
    });
    return found;
  }

private:
  const std::vector<Placed>& copies_;
  CopyGrid grid_;
};

// The candidate alternates (those whose place no kept copy of their type holds) and the kept copies
// within reach of them: the set the alternates are decided in. Candidates come first in the list.
struct AlternateRound {
  std::vector<Placed> copies;
  std::size_t candidates = 0;
};

AlternateRound alternate_round(std::vector<Placed> candidates, const std::vector<Placed>& copies,
                               const std::vector<char>& kept, const TypeShapes& t) {
  AlternateRound round;
  round.copies = std::move(candidates);
  round.candidates = round.copies.size();
  if (round.candidates == 0) return round;
  double widest_alternate = 0.0, widest_kept = 0.0;
  for (const Placed& a : round.copies) widest_alternate = std::max(widest_alternate, t.radius[a.type]);
  for (std::uint32_t i = 0; i < copies.size(); ++i)
    if (kept[i]) widest_kept = std::max(widest_kept, t.radius[copies[i].type]);
  CopyGrid candidate_grid(round.copies, widest_alternate + widest_kept);
  for (std::uint32_t i = 0; i < round.candidates; ++i) candidate_grid.add(i);
  for (std::uint32_t k = 0; k < copies.size(); ++k) {
    if (!kept[k]) continue;
    bool near = false;
    candidate_grid.around(copies[k].centre, [&](std::uint32_t c) {
      near = near || glm::length(copies[k].centre - round.copies[c].centre) < t.radius[copies[k].type] + t.radius[round.copies[c].type];
    });
    if (near) round.copies.push_back(copies[k]);
  }
  return round;
}

// Second round: each candidate alternate, fewer clashes first, is shown where it clashes with no
// kept copy nor shown alternate and no copy of its type holds its place (kSamePlace). A shown
// alternate is listed with the drops.
void show_alternates(const AlternateRound& round, const TypeShapes& t, double small_limit, float clearance, int threads,
                     PrunedMembrane& out) {
  const ClashSearch search(round.copies, t, small_limit, clearance);
  const std::vector<std::vector<std::uint32_t>> conflicts = conflict_lists(find_clashes(search, threads), round.copies.size(), out);
  std::vector<char> kept(round.copies.size(), 0);
  std::fill(kept.begin() + std::ptrdiff_t(round.candidates), kept.end(), 1);
  PlaceIndex shown(round.copies);  // the alternates shown so far (the kept copies' places were taken out before)
  std::vector<std::uint32_t> order(round.candidates);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return conflicts[a].size() < conflicts[b].size(); });
  for (const std::uint32_t i : order) {
    const Placed& a = round.copies[i];
    if (shown.taken(a) || std::any_of(conflicts[i].begin(), conflicts[i].end(), [&](std::uint32_t j) { return kept[j] != 0; }))
      continue;
    kept[i] = 1;
    shown.add(i);
    out.dropped[a.triangle].push_back(a.key);
    ++out.alternates_by_type[a.type];
  }
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
  const std::vector<Placed> copies = copies_to_check(mapping, shapes, region, settings, threads);
  out.checked_copies = copies.size();
  if (!settings.dropped_before.empty()) out.dropped = settings.dropped_before;
  if (copies.empty()) return out;

  const double small_limit = small_copy_limit(copies, shapes.radius);
  std::vector<char> kept;
  {
    const ClashSearch search(copies, shapes, small_limit, settings.clearance);
    kept = kept_copies(copies, conflict_lists(find_clashes(search, threads), copies.size(), out), shapes.radius, small_limit);
  }
  record_drops(copies, kept, out);
  PlaceIndex kept_places(copies);
  for (std::uint32_t i = 0; i < copies.size(); ++i)
    if (kept[i]) kept_places.add(i);
  std::vector<Placed> candidates = alternates_to_check(
      mapping, shapes, region, settings, [&](const Placed& a) { return !kept_places.taken(a); }, threads);
  out.checked_copies += candidates.size();
  if (!candidates.empty())
    show_alternates(alternate_round(std::move(candidates), copies, kept, shapes), shapes, small_limit, settings.clearance, threads, out);
  for (auto& keys : out.dropped) std::sort(keys.begin(), keys.end());
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
          if (m.type != type) return;
          const std::uint32_t key = mapping.copy_key(t, m);
          if (std::binary_search(dropped.begin(), dropped.end(), key)) return;
          copies.push_back({static_cast<std::uint32_t>(t), key, dvec3(mapping.centre_of(t, m))});
        },
        SeamRule::ignore, Instances::originals);
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
