#include "bake/tiles/unit_packer.hpp"

#include "bake/tiles/copy_neighbourhood.hpp"
#include "bake/tiles/rotation_sampling.hpp"
#include "common/parallel_for.hpp"
#include "common/progress.hpp"
#include "bake/tiles/tile_random.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <optional>

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
  std::vector<uint32_t> spec_of;  // per copy: the spec it was placed for
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

// Zone of a unit for one spec: centre within `band` of the anchor along mask axes, `band` inside
// the tile along the others. Zero volume when the tile is too small for an interior.
double zone_measure(unsigned mask, double band, int D, float edge) {
  double zone = 1.0;
  for (int a = 0; a < D; ++a) zone *= ((mask >> a) & 1u) ? 2.0 * band : std::max(0.0, edge - 2.0 * band);
  return zone;
}

bool in_zone(const glm::vec3& p, unsigned mask, double band, int D, float edge) {
  for (int a = 0; a < D; ++a) {
    const double v = p[a];
    if ((mask >> a) & 1u ? (v < -band || v > band) : (v < band || v > edge - band)) return false;
  }
  return true;
}

glm::quat random_orientation(const PlacementSpec& spec, SplitMix64& rng) {
  return spec.uniform_rotation ? uniform_rotation(rng)
                               : glm::normalize(spin_about_z(rng.uniform(0.0, 2.0 * M_PI)) * spec.base);
}

Instance random_copy(const PlacementSpec& spec, unsigned mask, int D, float edge, SplitMix64& rng) {
  const double b = spec.band;
  Instance copy{spec.type};
  for (int a = 0; a < D; ++a)
    copy.position[a] = static_cast<float>(((mask >> a) & 1u) ? rng.uniform(-b, b) : rng.uniform(b, edge - b));
  if (D == 2) copy.position.z = spec.z;
  copy.rotation = random_orientation(spec, rng);
  return copy;
}

// Symmetric, small random turn: about the tile z axis for membrane copies (they keep standing along
// the normal), about a uniformly random axis for solubles.
glm::quat small_turn(SplitMix64& rng, double max_angle, bool about_z_only) {
  const float angle = static_cast<float>(rng.uniform(-max_angle, max_angle));
  if (about_z_only) return spin_about_z(angle);
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * M_PI), r = std::sqrt(1.0 - z * z);
  return glm::angleAxis(angle, glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                                         static_cast<float>(z)));
}

// Every unit with the (unit, offset) pairs that can meet in some valid tiling, in both directions:
// exactly the pairs the sequential fill checks (it asks the later unit about the earlier one), so a
// copy moved, inserted or laid against all of them keeps every valid tiling collision-free.
class UnitWorld {
public:
  UnitWorld(std::vector<Unit>& units, const std::vector<CollisionShape>& shapes,
            const std::vector<PlacementSpec>& specs, const WangColouring& set, const PackerSettings& settings)
      : units_(units), shapes_(shapes), specs_(specs), D_(set.dims), S_(settings.edge), settings_(settings) {
    const size_t n = units_.size();
    meets_.resize(n * n);
    for (size_t a = 0; a < n; ++a)
      for (size_t b = 0; b < n; ++b)
        for (const Offset& d : neighbour_offsets(D_)) {
          const Offset back{-d[0], -d[1], -d[2]};
          // The sequential fill asks the later unit about the earlier one.
          const bool meet = a >= b ? can_meet(units_[a], units_[b], d, set) : can_meet(units_[b], units_[a], back, set);
          if (meet) meets_[a * n + b].push_back(d);
        }
    poses_.resize(n);
    lo_.assign(n, glm::vec3(INFINITY));
    hi_.assign(n, glm::vec3(-INFINITY));
    reach_.assign(n, 0.f);
    for (size_t a = 0; a < n; ++a)
      for (const Instance& copy : units_[a].copies) track(a, copy);
  }

  // Densification. Random sequential addition jams well below the densities of real cells
  // (haemoglobin at 5 mM: ~87%), worst in the interiors: the thin face and shared zones were filled
  // without seeing the interiors that will sit against them. Every copy of a `densify` spec may
  // move (hard-body Monte Carlo: a small random move is kept only when it stays in its zone and
  // clear of every copy it can meet), which turns the jammed packing into a fluid whose gaps wander
  // and merge, and new copies go where the gaps are largest. Adds the copies per tile it inserts to
  // achieved_per_tile (per spec).
  // Stops early once kStaleRounds rounds in a row insert nothing: the gaps no longer open up (a
  // request the surface cannot hold; without the stop a coarse mesh's bounds cost minutes).
  void run(std::vector<double>& achieved_per_tile, SplitMix64& rng) {
    const double measure = std::pow(static_cast<double>(S_), D_);
    int stale = 0;
    int round = 0;
    struct RoundsDone {  // every announced round counts as done, however the loop ends
      const int& round;
      int rounds;
      ~RoundsDone() { progress::advance(static_cast<std::uint64_t>(std::max(0, rounds - round))); }
    } rounds_done{round, settings_.relaxation_rounds};
    for (; round < settings_.relaxation_rounds && stale < kStaleRounds; ++round, progress::advance()) {
      bool short_any = false;
      for (size_t si = 0; si < specs_.size(); ++si)
        short_any |= specs_[si].densify && achieved_per_tile[si] < specs_[si].copies_per_volume * measure - 1e-9;
      if (!short_any) return;
      shake(rng);
      bool inserted = false;
      for (size_t si = 0; si < specs_.size(); ++si) {
        const double wanted = specs_[si].copies_per_volume * measure;
        if (!specs_[si].densify) continue;
        const int darts = static_cast<int>(std::ceil(settings_.relaxation_darts * static_cast<double>(units_.size())));
        for (int k = 0; k < darts && achieved_per_tile[si] < wanted - 1e-9; ++k) {
          const double added = insert(si, rng, wanted - achieved_per_tile[si]);
          achieved_per_tile[si] += added;
          inserted |= added > 0.0;
        }
      }
      stale = inserted ? 0 : stale + 1;
    }
  }

  // Decides every layer copy in every unit instance against the packed copies only (the layer is
  // clash-free with itself), then adds the kept ones. Returns kept copies per tile, per type.
  std::vector<double> lay(const FixedLayer& layer, SplitMix64& rng) {
    LayerLaying laying{layer, rule_, std::vector<char>(shapes_.size(), 0), {}};
    if (layer.clearance > 0.f) laying.rule.clearance = layer.clearance;
    for (const uint32_t type : layer.laid_through)
      if (type < laying.laid_through.size()) laying.laid_through[type] = 1;
    laying.per_tile.assign(shapes_.size(), 0.0);
    const LayerDecision decided = decide_layer(laying);
    for (const auto& [a, copy] : decided.kept) add(a, copy, kLayerSpec);
    refill_holes(laying, decided.refused, rng);
    for (const auto& [a, copy] : decided.alternates) add(a, copy, kLayerSpec);
    const double measure = std::pow(static_cast<double>(S_), D_);
    for (double& v : laying.per_tile) v /= measure;
    return laying.per_tile;
  }

private:
  static constexpr uint32_t kLayerSpec = ~0u;  // never shaken: the layer comes last
  static constexpr size_t kNone = ~size_t(0);

  struct LayerLaying {
    const FixedLayer& layer;
    ClashRule rule;                 // between a layer copy and a packed one
    std::vector<char> laid_through;  // per type
    std::vector<double> per_tile;    // per type: kept copies per tile
  };
  // Layer copies placed in unit instances: (unit, copy relative to its anchor).
  using UnitCopies = std::vector<std::pair<size_t, Instance>>;
  struct LayerDecision {
    UnitCopies kept, refused, alternates;
  };

  void add(size_t a, const Instance& copy, uint32_t spec) {
    units_[a].copies.push_back(copy);
    units_[a].spec_of.push_back(spec);
    track(a, copy);
  }

  // Each layer copy in each unit instance, decided side by side (they read the packed copies only),
  // gathered in the layer's order.
  LayerDecision decide_layer(LayerLaying& laying) const {
    const FixedLayer& layer = laying.layer;
    constexpr size_t kChunk = 64;
    const size_t chunks = (layer.copies.size() + kChunk - 1) / kChunk;
    std::vector<LayerDecision> decided(chunks);
    std::vector<std::vector<double>> per_tile(chunks, std::vector<double>(laying.per_tile.size(), 0.0));
    parallel_for(chunks, settings_.threads, [&](size_t chunk) {
      for (size_t i = chunk * kChunk; i < std::min(layer.copies.size(), (chunk + 1) * kChunk); ++i)
        decide_layer_copy(laying, layer.copies[i], decided[chunk], per_tile[chunk]);
    });
    LayerDecision out;
    for (size_t chunk = 0; chunk < chunks; ++chunk) {
      for (UnitCopies* list : {&out.kept, &out.refused, &out.alternates}) {
        const UnitCopies& from = list == &out.kept ? decided[chunk].kept : list == &out.refused ? decided[chunk].refused : decided[chunk].alternates;
        list->insert(list->end(), from.begin(), from.end());
      }
      for (size_t t = 0; t < per_tile[chunk].size(); ++t) laying.per_tile[t] += per_tile[chunk][t];
    }
    return out;
  }

  void decide_layer_copy(const LayerLaying& laying, const Instance& copy, LayerDecision& out, std::vector<double>& per_tile) const {
    const FixedLayer& layer = laying.layer;
    unsigned mask = 0;
    Instance local = copy;  // relative to the anchor of the unit holding it
    for (int k = 0; k < D_; ++k) {
      if (copy.position[k] < layer.band) mask |= 1u << k;
      if (copy.position[k] >= S_ - layer.band) {
        mask |= 1u << k;
        local.position[k] -= S_;
      }
    }
    for (size_t a = 0; a < units_.size(); ++a) {
      if (units_[a].mask != mask) continue;
      if (!fits(a, local, kNone, laying.rule, laying.laid_through)) {
        if (copy.alternate) continue;
        out.refused.emplace_back(a, local);
        if (layer.refused_stay_as_alternates) {
          Instance stand_in = local;
          stand_in.alternate = true;
          stand_in.has_alternate = false;
          out.alternates.emplace_back(a, stand_in);
        }
        continue;
      }
      if (copy.alternate) {  // overlaps its original by design: added last, and no part of the density
        out.alternates.emplace_back(a, local);
        continue;
      }
      out.kept.emplace_back(a, local);
      per_tile[copy.type] += units_[a].per_tile;
    }
  }

  // The layer copies a hole may be refilled from: its leaflet's, of its kind.
  class RefillPools {
  public:
    explicit RefillPools(const FixedLayer& layer) : kind_(layer.kind_of_type) {
      for (const Instance& c : layer.copies)
        if (!c.alternate) pools_[key(c)].push_back(&c);
    }
    const std::vector<const Instance*>& of(const Instance& hole) const {
      const auto found = pools_.find(key(hole));
      return found == pools_.end() ? none_ : found->second;
    }

  private:
    std::pair<bool, uint32_t> key(const Instance& c) const {
      return {c.position.z >= 0.f, c.type < kind_.size() ? kind_[c.type] : 0u};
    }
    const std::vector<uint32_t>& kind_;
    std::map<std::pair<bool, uint32_t>, std::vector<const Instance*>> pools_;
    std::vector<const Instance*> none_;
  };

  // Where a packed copy (a protein) pushed a layer lipid out, the hole would show what lies
  // beneath the membrane. Membrane builders pack lipids right against the protein: try other
  // conformers of the same leaflet and kind there, turned about the normal and moved away from the
  // protein, and keep the first that fits.
  // Each hole's candidates are tried side by side against what stands before any refill, each hole
  // with its own random stream; then, in order, a hole keeps its find if it still fits beside the
  // refills kept before it, else tries again alone. The same set whatever the threads.
  void refill_holes(LayerLaying& laying, const UnitCopies& refused, SplitMix64& rng) {
    if (D_ != 2 || refused.empty()) return;
    const RefillPools pools(laying.layer);
    float layer_reach = 0.f;
    for (const Instance& c : laying.layer.copies) layer_reach = std::max(layer_reach, shapes_[c.type].radius());
    const uint64_t stream = rng.next();
    std::vector<std::optional<Instance>> found(refused.size());
    std::vector<glm::vec2> away(refused.size());
    parallel_for(refused.size(), settings_.threads, [&](size_t h) {
      const auto& [a, hole] = refused[h];
      const std::vector<const Instance*>& pool = pools.of(hole);
      if (pool.empty()) return;
      away[h] = away_from_intruder(a, hole, layer_reach, laying.laid_through);
      SplitMix64 own(mix64(stream ^ mix64(h + 1)));
      found[h] = refill_candidate(laying, a, hole, pool, away[h], own);
    });
    for (size_t h = 0; h < refused.size(); ++h) {
      const auto& [a, hole] = refused[h];
      const std::vector<const Instance*>& pool = pools.of(hole);
      if (pool.empty()) continue;
      std::optional<Instance> candidate = found[h];
      if (candidate && !fits(a, *candidate, kNone, laying.rule, laying.laid_through)) {
        SplitMix64 again(mix64(stream ^ mix64(h + 1) ^ 0x5EED5EEDull));
        candidate = refill_candidate(laying, a, hole, pool, away[h], again);
      }
      if (!candidate) continue;
      add(a, *candidate, kLayerSpec);
      laying.per_tile[candidate->type] += units_[a].per_tile;
    }
  }

  // The copy that pushed the lipid out is the one reaching deepest into its place: candidates go
  // from the hole away from it, into the rim a protein leaves between itself and the layer.
  glm::vec2 away_from_intruder(size_t a, const Instance& hole, float layer_reach, const std::vector<char>& laid_through) const {
    glm::vec2 away(0.f);
    float deepest = INFINITY;
    any_near(a, hole.position, layer_reach, kNone, [&](uint32_t type, const Pose& other) {
      const glm::vec2 d = glm::vec2(hole.position) - glm::vec2(other.position);
      const float gap = glm::length(d) - shapes_[type].radius();
      if (!laid_through[type] && shapes_[type].radius() > layer_reach && gap < deepest && glm::dot(d, d) > 0.f) {
        deepest = gap;
        away = glm::normalize(d);
      }
      return false;
    });
    return away;
  }

  // The first of refill_attempts conformers of the hole's leaflet, turned and moved away from what
  // pushed the lipid out, that fits where everything stands now.
  std::optional<Instance> refill_candidate(const LayerLaying& laying, size_t a, const Instance& hole,
                                           const std::vector<const Instance*>& pool, glm::vec2 away, SplitMix64& rng) const {
    const glm::vec2 across(-away.y, away.x);
    for (int attempt = 0; attempt < laying.layer.refill_attempts; ++attempt) {
      const Instance& conformer = *pool[rng.below(static_cast<uint32_t>(pool.size()))];
      Instance candidate = conformer;
      const glm::vec2 shift = attempt == 0 ? glm::vec2(0.f)
                                           : away * static_cast<float>(rng.uniform(0.0, 8.0)) +
                                                 across * static_cast<float>(rng.uniform(-3.0, 3.0));
      for (int k = 0; k < 2; ++k) candidate.position[k] = hole.position[k] + shift[k];
      candidate.rotation = glm::normalize(spin_about_z(static_cast<float>(rng.uniform(0.0, 2.0 * M_PI))) * conformer.rotation);
      if (!in_zone(candidate.position, units_[a].mask, laying.layer.band, D_, S_) ||
          !fits(a, candidate, kNone, laying.rule, laying.laid_through))
        continue;
      return candidate;
    }
    return std::nullopt;
  }

  void track(size_t a, const Instance& copy) {
    poses_[a].push_back(pose_of(copy, {0, 0, 0}, D_, S_));
    widen(a, copy);
  }
  // Boxes only grow, so they stay conservative as copies move.
  void widen(size_t a, const Instance& copy) {
    lo_[a] = glm::min(lo_[a], copy.position);
    hi_[a] = glm::max(hi_[a], copy.position);
    reach_[a] = std::max(reach_[a], shapes_[copy.type].radius());
  }

  // Calls f(pose of another copy) for every copy that unit a's candidate at p could touch, within
  // `reach` of p (beyond the other's bounding sphere), skipping copy `skip` of unit a itself; stops
  // when f returns true.
  template <class F>
  bool any_near(size_t a, const glm::vec3& p, float reach, size_t skip, F&& f) const {
    const size_t n = units_.size();
    for (size_t b = 0; b < n; ++b) {
      if (poses_[b].empty()) continue;
      for (const Offset& d : meets_[a * n + b]) {
        glm::vec3 shift(0.f);
        for (int k = 0; k < D_; ++k) shift[k] = S_ * static_cast<float>(d[k]);
        const glm::vec3 gap = glm::max(glm::max(lo_[b] + shift - p, p - hi_[b] - shift), glm::vec3(0.f));
        const float height = std::max(std::abs(p.z) + reach, std::max(std::abs(lo_[b].z), std::abs(hi_[b].z)) + reach_[b]);
        const float limit = (reach + reach_[b]) / rule_.closest_scale(height);
        if (glm::dot(gap, gap) >= limit * limit) continue;
        for (size_t j = 0; j < poses_[b].size(); ++j) {
          if (b == a && j == skip) continue;
          Pose other = poses_[b][j];
          other.position += shift;
          if (f(units_[b].copies[j].type, other)) return true;
        }
      }
    }
    return false;
  }

  bool fits(size_t a, const Instance& copy, size_t skip) const { return fits(a, copy, skip, rule_); }
  // `ignored`: types (indexed by type) this copy may overlap.
  bool fits(size_t a, const Instance& copy, size_t skip, const ClashRule& rule,
            const std::vector<char>& ignored = {}) const {
    Offset owner;
    if (!owner_shift(copy, units_[a].mask, D_, S_, owner)) return false;
    const CollisionShape& shape = shapes_[copy.type];
    const Pose pose = pose_of(copy, {0, 0, 0}, D_, S_);
    return !any_near(a, pose.position, shape.radius(), skip, [&](uint32_t type, const Pose& other) {
      if (type < ignored.size() && ignored[type]) return false;
      return copies_collide(shape, pose, shapes_[type], other, rule);
    });
  }

  void shake(SplitMix64& rng) {
    for (size_t a = 0; a < units_.size(); ++a)
      for (size_t i = 0; i < units_[a].copies.size(); ++i) {
        const PlacementSpec& spec = specs_[units_[a].spec_of[i]];
        if (!spec.densify) continue;
        Instance moved = units_[a].copies[i];
        const double step = settings_.relaxation_step * spec.band;
        for (int k = 0; k < D_; ++k) moved.position[k] += static_cast<float>(rng.uniform(-step, step));
        moved.rotation =
            glm::normalize(small_turn(rng, 2.0 * settings_.relaxation_step, !spec.uniform_rotation) * moved.rotation);
        if (!in_zone(moved.position, units_[a].mask, spec.band, D_, S_) || !fits(a, moved, i)) continue;
        units_[a].copies[i] = moved;
        poses_[a][i] = pose_of(moved, {0, 0, 0}, D_, S_);
        widen(a, moved);
      }
  }

  // One insertion attempt for spec si: a unit drawn in proportion to how much of a tile its zone
  // covers, the emptiest of a few random points of the zone (largest distance to the bounding
  // spheres around it), a few orientations there. Returns the copies per tile added. Only units
  // whose copy brings the density closer to the request take part: a copy in a unit shared by
  // every tile adds a whole copy per tile, and short by a tenth of one, adding it would overshoot
  // ninefold (a protein at 200 per µm² came out at 1540).
  double insert(size_t si, SplitMix64& rng, double shortfall_per_tile) {
    const PlacementSpec& spec = specs_[si];
    double total = 0.0;
    std::vector<double> weight(units_.size());
    for (size_t a = 0; a < units_.size(); ++a)
      total += weight[a] = units_[a].per_tile < 2.0 * shortfall_per_tile
                               ? units_[a].per_tile * zone_measure(units_[a].mask, spec.band, D_, S_)
                               : 0.0;
    if (!(total > 0.0)) return 0.0;
    double pick = rng.uniform(0.0, total);
    size_t a = 0;
    while (a + 1 < units_.size() && (pick -= weight[a]) >= 0.0) ++a;
    const float radius = shapes_[spec.type].radius();
    Instance best;
    float best_room = -INFINITY;
    for (int k = 0; k < kVoidProbes; ++k) {
      const Instance probe = random_copy(spec, units_[a].mask, D_, S_, rng);
      float room = INFINITY;
      any_near(a, probe.position, 2.f * radius, kNone, [&](uint32_t type, const Pose& other) {
        room = std::min(room, glm::length(other.position - probe.position) - shapes_[type].radius());
        return false;
      });
      if (room > best_room) best_room = room, best = probe;
    }
    for (int k = 0; k < kTurns; ++k) {
      if (k > 0) best.rotation = random_orientation(spec, rng);
      if (!fits(a, best, kNone)) continue;
      add(a, best, static_cast<uint32_t>(si));
      return units_[a].per_tile;
    }
    return 0.0;
  }

  static constexpr int kVoidProbes = 8, kTurns = 6, kStaleRounds = 25;
  std::vector<Unit>& units_;
  const std::vector<CollisionShape>& shapes_;
  const std::vector<PlacementSpec>& specs_;
  int D_;
  float S_;
  const PackerSettings& settings_;
  const ClashRule rule_ = clash_rule(settings_, D_);
  std::vector<std::vector<Offset>> meets_;
  std::vector<std::vector<Pose>> poses_;
  std::vector<glm::vec3> lo_, hi_;
  std::vector<float> reach_;
};

}  // namespace

ClashRule clash_rule(const PackerSettings& settings, int dims) {
  if (dims != 2) return {settings.clearance, {}};
  return {settings.clearance, settings.surface};
}

namespace {

constexpr double kSharedOvershoot = 0.1;  // of a spec's request, the most a shared or face unit may pass it by

// What the sequential fill reads.
struct Packing {
  const std::vector<CollisionShape>& shapes;
  const std::vector<PlacementSpec>& specs;
  const WangColouring& set;
  const PackerSettings& settings;
};

// What the sequential fill carries from unit to unit.
struct Fill {
  std::vector<Offset> offsets;  // neighbour_offsets of the lattice
  float largest;                // largest radius among the specs' types, at least 1 Å
  SplitMix64 rng;
  std::vector<double> carry, achieved;  // per spec: rounding shortfall passed on; copies per tile placed
};

// Copies of each spec unit u aims for: density × zone, plus the shortfall `carry` passes on (in
// copies per tile), rounded. A shared or face unit's copy counts `per_tile` copies per tile at once,
// so it never takes the whole request (`achieved` so far, per tile) more than kSharedOvershoot past
// it: the interiors, 1/n per tile each, take the rest finely. Rounding a rare molecule up in a unit
// every tile holds was a whole copy per tile where 0.63 were asked (+59 %, IgG in 250 Å cubes);
// refusing any overshoot left a large one to interiors too small to hold it (−76 %, a 108 Å sphere
// at 0.46 a cube of 452 Å, where a face copy gives 0.5).
std::vector<long> unit_targets(const Packing& p, const Unit& u, const std::vector<double>& carry,
                               const std::vector<double>& achieved) {
  std::vector<long> target(p.specs.size(), 0);
  const double tile_measure = std::pow(static_cast<double>(p.settings.edge), p.set.dims);
  for (size_t si = 0; si < p.specs.size(); ++si) {
    const double zone = zone_measure(u.mask, p.specs[si].band, p.set.dims, p.settings.edge);
    const double want = p.specs[si].copies_per_volume * zone + carry[si] / u.per_tile;
    target[si] = zone > 0.0 ? std::max(0L, static_cast<long>(std::floor(want + 0.5))) : 0L;
    if (u.kind != Kind::Interior) {
      const double request = p.specs[si].copies_per_volume * tile_measure;
      const double room = (1.0 + kSharedOvershoot) * request - achieved[si];
      target[si] = std::min(target[si], std::max(0L, static_cast<long>(std::floor(room / u.per_tile + 1e-9))));
    }
  }
  return target;
}

// Random darts into unit ui, against the units filled before it that it can meet (and its own copies
// one lattice step away), towards `target` copies per spec; returns how many it placed of each.
std::vector<long> fill_unit(const Packing& p, std::vector<Unit>& units, size_t ui, const std::vector<Offset>& offsets,
                            float largest, const std::vector<long>& target, SplitMix64& rng) {
  const auto& [shapes, specs, set, settings] = p;
  const int D = set.dims;
  const float S = settings.edge;
  Unit& u = units[ui];
  CopyNeighbourhood context(shapes, 2.f * largest);
  for (size_t vi = 0; vi < ui; ++vi)
    for (const Offset& d : offsets)
      if (can_meet(u, units[vi], d, set))
        for (const Instance& copy : units[vi].copies) context.add(copy.type, pose_of(copy, d, D, S));
  std::vector<Offset> self;
  for (const Offset& d : offsets)
    if (can_meet(u, u, d, set)) self.push_back(d);

  std::vector<long> placed(specs.size(), 0);
  for (size_t si = 0; si < specs.size(); ++si) {
    const PlacementSpec& spec = specs[si];
    const double budget = static_cast<double>(target[si]) * settings.attempts_per_copy;
    long misses = 0;
    for (double attempts = 0; placed[si] < target[si] && attempts < budget && misses < settings.max_consecutive_failures;
         ++attempts) {
      const Instance copy = random_copy(spec, u.mask, D, S, rng);
      Offset shift;
      if (!owner_shift(copy, u.mask, D, S, shift) ||
          context.collides(copy.type, pose_of(copy, {0, 0, 0}, D, S), clash_rule(settings, D))) {
        ++misses;
        continue;
      }
      misses = 0;
      ++placed[si];
      u.copies.push_back(copy);
      u.spec_of.push_back(static_cast<uint32_t>(si));
      for (const Offset& d : self) context.add(copy.type, pose_of(copy, d, D, S));
    }
  }
  return placed;
}

// What unit u's fill leaves the next: the shortfall against density × zone, and what it placed.
void account(const Packing& p, const Unit& u, const std::vector<long>& placed, Fill& fill) {
  for (size_t si = 0; si < p.specs.size(); ++si) {
    const double ideal = p.specs[si].copies_per_volume * zone_measure(u.mask, p.specs[si].band, p.set.dims, p.settings.edge);
    fill.carry[si] += u.per_tile * (ideal - static_cast<double>(placed[si]));
    fill.achieved[si] += u.per_tile * static_cast<double>(placed[si]);
  }
}

// The shared and face units in order, each against all before it; then the tiles' interiors, which
// meet only those (never each other), side by side, each with its own random stream and its target
// set in order as if the ones before it had reached theirs.
void fill_units(const Packing& p, std::vector<Unit>& units, Fill& fill) {
  size_t first_interior = 0;
  while (first_interior < units.size() && units[first_interior].kind != Kind::Interior) ++first_interior;
  for (size_t ui = 0; ui < first_interior; ++ui) {
    progress::advance();
    account(p, units[ui],
            fill_unit(p, units, ui, fill.offsets, fill.largest, unit_targets(p, units[ui], fill.carry, fill.achieved), fill.rng),
            fill);
  }
  // The shortfall the shared units leave is spread over the interiors in equal shares, each passing
  // on what its rounding leaves: a unit asked for the whole of it at once cannot hold a large
  // molecule many times (a 108 Å sphere at 0.4 a cube: the first interior asked for 25, the rest
  // for none, 19 % placed).
  const size_t interiors = units.size() - first_interior;
  std::vector<std::vector<long>> targets(interiors), placed(interiors);
  std::vector<double> share = fill.carry, residual(p.specs.size(), 0.0);
  for (double& s : share) s /= static_cast<double>(std::max<size_t>(interiors, 1));
  for (size_t k = 0; k < interiors; ++k) {
    const Unit& u = units[first_interior + k];
    std::vector<double> carry(p.specs.size());
    for (size_t si = 0; si < p.specs.size(); ++si) carry[si] = share[si] + residual[si];
    targets[k] = unit_targets(p, u, carry, fill.achieved);
    for (size_t si = 0; si < p.specs.size(); ++si)
      residual[si] = carry[si] + u.per_tile * (p.specs[si].copies_per_volume *
                                                   zone_measure(u.mask, p.specs[si].band, p.set.dims, p.settings.edge) -
                                               static_cast<double>(targets[k][si]));
  }
  const uint64_t stream = fill.rng.next();
  parallel_for(interiors, p.settings.threads, [&](size_t k) {
    SplitMix64 rng(mix64(stream ^ mix64(k + 1)));
    placed[k] = fill_unit(p, units, first_interior + k, fill.offsets, fill.largest, targets[k], rng);
  });
  for (size_t k = 0; k < interiors; ++k) account(p, units[first_interior + k], placed[k], fill);
}

// Each tile gathers the copies of the units it holds: every shared and interior unit of its own, and
// the face units whose colour its faces carry.
std::vector<WangTile> assemble_tiles(const std::vector<Unit>& units, const std::vector<CollisionShape>& shapes,
                                     const WangColouring& set, float S) {
  const int D = set.dims;
  std::vector<WangTile> tiles(set.tile_count());
  for (uint32_t t = 0; t < set.tile_count(); ++t) {
    WangTile& tile = tiles[t];
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
  return tiles;
}

}  // namespace

PackedUnits pack_wang_units(const std::vector<CollisionShape>& shapes, const std::vector<PlacementSpec>& specs,
                            const WangColouring& set, const PackerSettings& settings, const FixedLayer& layer) {
  std::vector<Unit> units = make_units(set);
  Fill fill{neighbour_offsets(set.dims), 1.f, SplitMix64(mix64(settings.seed ^ 0xA5A5F00Dull)),
            std::vector<double>(specs.size(), 0.0), std::vector<double>(specs.size(), 0.0)};
  for (const PlacementSpec& s : specs) fill.largest = std::max(fill.largest, shapes[s.type].radius());
  // Progress counts units packed, then relaxation rounds (all announced; those an early stop skips
  // are marked done when it stops).
  // (the interiors, one per tile, count themselves as they are filled side by side)
  progress::add_work(units.size() - set.tile_count() + static_cast<std::uint64_t>(std::max(settings.relaxation_rounds, 0)));
  fill_units({shapes, specs, set, settings}, units, fill);

  PackedUnits out;
  if (settings.relaxation_rounds > 0 || !layer.copies.empty()) {
    UnitWorld world(units, shapes, specs, set, settings);
    if (settings.relaxation_rounds > 0) world.run(fill.achieved, fill.rng);
    if (!layer.copies.empty()) out.layer_per_volume = world.lay(layer, fill.rng);
  }
  out.tiles = assemble_tiles(units, shapes, set, settings.edge);
  const double measure = std::pow(static_cast<double>(settings.edge), set.dims);
  for (double a : fill.achieved) out.achieved_per_volume.push_back(a / measure);
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
