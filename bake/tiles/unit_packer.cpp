#include "bake/tiles/unit_packer.hpp"

#include "bake/tiles/copy_neighbourhood.hpp"
#include "bake/tiles/rotation_sampling.hpp"
#include "bake/tiles/tile_random.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace nano::tiles {
namespace {

enum class Kind { Shared, Face, Interior };

struct Unit {
  Kind kind;
  unsigned mask;   // lattice axes whose anchor planes the copies may cross
  int axis = -1;   // Face
  int colour = -1; // Face
  uint32_t tile = 0;  // Interior
  double per_tile = 1.0;  // how often the unit occurs per tile of a uniform tiling
  std::vector<Instance> copies;  // positions relative to the anchor
};

using Offset = std::array<int, 3>;

std::vector<Unit> make_units(const WangColouring& set) {
  const int D = set.dims;
  std::vector<Unit> units;
  for (int crossed = D; crossed >= 2; --crossed)
    for (unsigned mask = 1; mask < (1u << D); ++mask)
      if (std::popcount(mask) == crossed) units.push_back({Kind::Shared, mask});
  for (int a = 0; a < D; ++a)
    for (int c = 0; c < set.colours; ++c)
      units.push_back({Kind::Face, 1u << a, a, c, 0, 1.0 / set.colours});
  for (uint32_t t = 0; t < set.tile_count(); ++t)
    units.push_back({Kind::Interior, 0u, -1, -1, t, 1.0 / set.tile_count()});
  return units;
}

// Unit u anchored at 0 covers tiles -s (s a 0/1 vector within its mask), unit v anchored at d covers
// d - s': they share a tile iff d = s' - s for some such s, s'.
bool supports_meet(unsigned mask_u, unsigned mask_v, const Offset& d, int D) {
  for (int a = 0; a < D; ++a) {
    const bool in_u = (mask_u >> a) & 1u, in_v = (mask_v >> a) & 1u;
    const int lo = in_u ? -1 : 0, hi = in_v ? 1 : 0;
    if (d[a] < lo || d[a] > hi) return false;
  }
  return true;
}

// Can unit v at offset d sit next to unit u (at 0, filled later or the same unit) in some valid
// tiling, close enough to touch? Conservative: only combinations no tiling can produce are excluded.
bool can_meet(const Unit& u, const Unit& v, const Offset& d, const WangColouring& set) {
  if (!supports_meet(u.mask, v.mask, d, set.dims)) return false;
  if (&u == &v || u.kind == Kind::Shared || v.kind == Kind::Shared) return true;
  if (u.kind == Kind::Face && v.kind == Kind::Face) {
    const bool same_face = u.axis == v.axis && d == Offset{0, 0, 0};
    return !same_face || u.colour == v.colour;
  }
  if (u.kind == Kind::Interior && v.kind == Kind::Face)  // one of the tile's own faces: d is 0 or e_axis
    return set.tiles[u.tile][v.axis][d[v.axis]] == v.colour;
  return false;  // two interiors: different tiles never share a tile
}

std::vector<Offset> neighbour_offsets(int D) {
  std::vector<Offset> out;
  for (int z = (D == 3 ? -1 : 0); z <= (D == 3 ? 1 : 0); ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) out.push_back({x, y, z});
  return out;
}

Pose pose_of(const Instance& copy, const Offset& d, int D, float edge) {
  Pose p{copy.position, glm::mat3_cast(copy.rotation)};
  for (int a = 0; a < D; ++a) p.position[a] += edge * static_cast<float>(d[a]);
  return p;
}

// Where a copy lands in the tile owning its centre: shift by one edge along mask axes where it lies
// below the anchor. Empty when float rounding would push it onto the tile's excluded upper side.
bool owner_shift(const Instance& copy, unsigned mask, int D, float edge, Offset& shift) {
  shift = {0, 0, 0};
  for (int a = 0; a < D; ++a) {
    if (((mask >> a) & 1u) && copy.position[a] < 0.f) shift[a] = 1;
    const float t = copy.position[a] + edge * static_cast<float>(shift[a]);
    if (!(t >= 0.f && t < edge)) return false;
  }
  return true;
}

}  // namespace

PackedUnits pack_wang_units(const std::vector<CollisionShape>& shapes, const std::vector<PlacementSpec>& specs,
                            const WangColouring& set, const PackerSettings& settings) {
  const int D = set.dims;
  const float S = settings.edge;
  std::vector<Unit> units = make_units(set);
  const std::vector<Offset> offsets = neighbour_offsets(D);

  float largest = 1.f;
  for (const PlacementSpec& s : specs) largest = std::max(largest, shapes[s.type].radius());

  SplitMix64 rng(mix64(settings.seed ^ 0xA5A5F00Dull));
  std::vector<double> carry(specs.size(), 0.0), achieved(specs.size(), 0.0);

  for (size_t ui = 0; ui < units.size(); ++ui) {
    Unit& u = units[ui];
    CopyNeighbourhood context(shapes, 2.f * largest);
    for (size_t vi = 0; vi < ui; ++vi)
      for (const Offset& d : offsets)
        if (can_meet(u, units[vi], d, set))
          for (const Instance& copy : units[vi].copies) context.add(copy.type, pose_of(copy, d, D, S));
    std::vector<Offset> self;
    for (const Offset& d : offsets)
      if (can_meet(u, u, d, set)) self.push_back(d);

    for (size_t si = 0; si < specs.size(); ++si) {
      const PlacementSpec& spec = specs[si];
      const double b = spec.band;
      double zone = 1.0;
      for (int a = 0; a < D; ++a) zone *= ((u.mask >> a) & 1u) ? 2.0 * b : std::max(0.0, S - 2.0 * b);
      const double ideal = spec.copies_per_volume * zone;
      const double want = ideal + carry[si] / u.per_tile;
      const long target = zone > 0.0 ? std::max(0L, static_cast<long>(std::floor(want + 0.5))) : 0L;
      const double budget = static_cast<double>(target) * settings.attempts_per_copy;
      long placed = 0, misses = 0;
      for (double attempts = 0; placed < target && attempts < budget && misses < settings.max_consecutive_failures;
           ++attempts) {
        Instance copy{spec.type};
        for (int a = 0; a < D; ++a)
          copy.position[a] = static_cast<float>(((u.mask >> a) & 1u) ? rng.uniform(-b, b) : rng.uniform(b, S - b));
        if (D == 2) copy.position.z = spec.z;
        copy.rotation = spec.uniform_rotation ? uniform_rotation(rng)
                                              : glm::normalize(spin_about_z(rng.uniform(0.0, 2.0 * M_PI)) * spec.base);
        Offset shift;
        if (!owner_shift(copy, u.mask, D, S, shift) ||
            context.collides(copy.type, pose_of(copy, {0, 0, 0}, D, S), settings.clearance)) {
          ++misses;
          continue;
        }
        misses = 0;
        ++placed;
        u.copies.push_back(copy);
        for (const Offset& d : self) context.add(copy.type, pose_of(copy, d, D, S));
      }
      carry[si] += u.per_tile * (ideal - static_cast<double>(placed));
      achieved[si] += u.per_tile * static_cast<double>(placed);
    }
  }

  PackedUnits out;
  out.tiles.resize(set.tile_count());
  for (uint32_t t = 0; t < set.tile_count(); ++t) {
    WangTile& tile = out.tiles[t];
    tile.colours = set.tiles[t];
    for (const Unit& u : units) {
      if (u.kind == Kind::Interior && u.tile != t) continue;
      for (const Instance& copy : u.copies) {
        Offset shift;
        owner_shift(copy, u.mask, D, S, shift);  // always true: checked when the copy was placed
        if (u.kind == Kind::Face && set.tiles[t][u.axis][shift[u.axis]] != u.colour) continue;
        Instance placed = copy;
        for (int a = 0; a < D; ++a) placed.position[a] += S * static_cast<float>(shift[a]);
        tile.instances.push_back(placed);
      }
    }
    compute_atom_bounds(tile, shapes);
  }
  const double measure = std::pow(static_cast<double>(S), D);
  for (double a : achieved) out.achieved_per_volume.push_back(a / measure);
  return out;
}

void compute_atom_bounds(WangTile& tile, const std::vector<CollisionShape>& shapes) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const Instance& in : tile.instances) {
    const glm::mat3 r = glm::mat3_cast(in.rotation);
    for (const AtomSphere& a : shapes[in.type].atoms()) {
      const glm::vec3 c = in.position + r * a.centre;
      lo = glm::min(lo, c - a.radius);
      hi = glm::max(hi, c + a.radius);
    }
  }
  if (tile.instances.empty()) lo = hi = glm::vec3(0.f);
  tile.atoms_min = lo;
  tile.atoms_max = hi;
}

}  // namespace nano::tiles
