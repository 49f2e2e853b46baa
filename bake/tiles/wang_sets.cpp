#include "bake/tiles/wang_sets.hpp"

#include "bake/tiles/copy_neighbourhood.hpp"
#include "bake/tiles/rotation_sampling.hpp"
#include "bake/tiles/tile_random.hpp"
#include "bake/tiles/unit_packer.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>

namespace nano::tiles {
namespace {

constexpr double kAvogadro = 6.02214076e23;
constexpr double kA2PerUm2 = 1e8, kA3PerUm3 = 1e12;
constexpr int kMixAttempts = 400;  // best-ranked conformer turns tried in a place given to a mixed species
constexpr int kSpins = 12;        // turns about the normal ranked per conformer
constexpr std::size_t kNudgedCandidates = 100;  // best-ranked turns also tried moved by kNudge along x and y
constexpr float kNudge = 0.8f;                  // Å

struct Wanted {
  PlacementSpec spec;
  double requested_per_um;  // per µm² or µm³
  bool required;
};

std::string number(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

void check_common(const char* what, float edge, const std::vector<MoleculeType>& types, const GenerationBudget& b) {
  if (!(edge > 0.f) || !std::isfinite(edge)) throw InputError(what, "edge", "tile edge must be a positive length (Å)");
  if (!(b.clearance > 0.f) || b.clearance > 2.f) throw InputError(what, "clearance", "clearance must be in (0, 2]");
  if (b.attempts_per_copy < 1 || b.max_consecutive_failures < 1 || b.relaxation_rounds < 0)
    throw InputError(what, "budget", "attempt budgets must be positive (relaxation rounds >= 0)");
  if (types.empty()) throw InputError(what, "types", "no molecule types given");
}

void check_type(const char* what, const std::vector<MoleculeType>& types, uint32_t type, double density) {
  if (type >= types.size()) throw InputError(what, "molecules", "molecule type index " + std::to_string(type) + " out of range");
  if (!(density >= 0.0) || !std::isfinite(density))
    throw InputError(what, types[type].name, "density must be a finite number >= 0");
}

void check_fits(const char* what, const MoleculeType& type, float band, float edge) {
  if (2.f * band > edge)
    throw InputError(what, type.name,
                     "molecule spans " + number(2.0 * band) + " Å across the tile lattice, more than the tile edge " +
                         number(edge) + " Å");
}

// Largest molecules first: dart throwing places big ones while there is room.
WangSet pack(const char* what, int dims, float edge, const WangColouring& colouring,
             const std::vector<MoleculeType>& types, const std::vector<CollisionShape>& shapes,
             std::vector<Wanted> wanted, uint64_t seed, const GenerationBudget& budget, SurfaceDistortion surface = {},
             const FixedLayer& layer = {}, const std::vector<double>& layer_requested = {}) {
  std::stable_sort(wanted.begin(), wanted.end(), [&](const Wanted& a, const Wanted& b) {
    if (a.required != b.required) return a.required;
    return shapes[a.spec.type].radius() > shapes[b.spec.type].radius();
  });
  std::vector<PlacementSpec> specs;
  for (const Wanted& w : wanted) specs.push_back(w.spec);
  const PackedUnits packed = pack_wang_units(
      shapes, specs, colouring,
      {edge, budget.clearance, surface, seed, budget.attempts_per_copy, budget.max_consecutive_failures,
       budget.relaxation_rounds, 0.25f, 4.f, budget.threads},
      layer);

  WangSet set{dims, edge, colouring, packed.tiles, {}};
  const double scale = dims == 2 ? kA2PerUm2 : kA3PerUm3;
  for (size_t i = 0; i < wanted.size(); ++i) {
    const uint32_t type = wanted[i].spec.type;
    auto it = std::find_if(set.densities.begin(), set.densities.end(), [&](const MoleculeDensity& d) { return d.type == type; });
    if (it == set.densities.end()) {
      set.densities.push_back({types[type].name, type, 0.0, 0.0, 0});
      it = set.densities.end() - 1;
    }
    it->requested += wanted[i].requested_per_um;
    it->achieved += packed.achieved_per_volume[i] * scale;
  }
  for (uint32_t type = 0; type < packed.layer_per_volume.size(); ++type)
    if (layer_requested[type] > 0.0 || packed.layer_per_volume[type] > 0.0)
      set.densities.push_back(
          {types[type].name, type, layer_requested[type], packed.layer_per_volume[type] * scale, 0});
  for (const WangTile& tile : set.tiles)
    for (const Instance& in : tile.instances)
      for (MoleculeDensity& d : set.densities)
        if (d.type == in.type) ++d.copies_in_set;
  for (size_t i = 0; i < wanted.size(); ++i) {
    if (!wanted[i].required) continue;
    const MoleculeDensity& d = *std::find_if(set.densities.begin(), set.densities.end(),
                                             [&](const MoleculeDensity& m) { return m.type == wanted[i].spec.type; });
    // A set holds whole copies: short by less than half a copy of the whole set is as close as
    // it can come (200 per µm² in 16 tiles of 191 Å is 1.17 copies; one copy is 171 per µm²).
    const double set_measure = std::pow(static_cast<double>(edge), dims) * static_cast<double>(colouring.tile_count());
    const double copies_short = (d.requested - d.achieved) / scale * set_measure;
    if (d.achieved < 0.9 * d.requested && copies_short >= 0.5)
      throw InputError(what, d.name,
                       "requested " + number(d.requested) + (dims == 2 ? " copies/µm²" : " copies/µm³") +
                           " cannot be reached without collisions; best achieved " + number(d.achieved));
  }
  return set;
}

std::vector<CollisionShape> shapes_of(const std::vector<MoleculeType>& types) {
  std::vector<CollisionShape> shapes;
  for (const MoleculeType& t : types) shapes.emplace_back(t);
  return shapes;
}

// What laying a lipid patch over one tile reads.
struct PatchLaying {
  const char* what;
  const LipidPatch& patch;
  float edge;
  const std::vector<MoleculeType>& types;
  const std::vector<CollisionShape>& shapes;
  ClashRule rule;  // between the patch's lipids
};

// How much of each leaflet's places the mixed species take.
struct LeafletShares {
  double outer = 0.0, inner = 0.0;
};

LeafletShares check_patch(const PatchLaying& p) {
  const LipidPatch& patch = p.patch;
  for (float period : {patch.period_x, patch.period_y})
    if (!(period > 0.f) || !std::isfinite(period)) throw InputError(p.what, "lipid patch", "the patch period must be positive");
  if (patch.lipids.empty()) throw InputError(p.what, "lipid patch", "the patch has no lipids");
  if (!(patch.clearance > 0.f) || patch.clearance > 2.f)
    throw InputError(p.what, "lipid patch", "the patch clearance must be in (0, 2]");
  LeafletShares taken;
  for (const LipidSpecies& species : patch.mix) {
    if (!(species.outer >= 0.f) || !(species.inner >= 0.f) || species.conformers.empty())
      throw InputError(p.what, "lipid mix", "a mixed species needs conformers and fractions >= 0");
    taken.outer += species.outer;
    taken.inner += species.inner;
    for (const Instance& c : species.conformers) check_type(p.what, p.types, c.type, 1.0);
  }
  if (taken.outer > 1.0 + 1e-6 || taken.inner > 1.0 + 1e-6)
    throw InputError(p.what, "lipid mix", "the mixed species take more than all of a leaflet's places");
  return taken;
}

// Adds what each lipid asks per µm² to `requested` and widens `band` to every lipid and conformer;
// returns the largest radius among them.
float request_places(const PatchLaying& p, LeafletShares mixed, float& band, std::vector<double>& requested) {
  const LipidPatch& patch = p.patch;
  float largest = 0.f;
  for (const Instance& l : patch.lipids) {
    check_type(p.what, p.types, l.type, 1.0);
    if (!std::isfinite(l.position.x) || !std::isfinite(l.position.y) || !std::isfinite(l.position.z))
      throw InputError(p.what, p.types[l.type].name, "patch lipid positions must be finite");
    // Each place asks for the base species by what the mix leaves it, and for each mixed species
    // by its fraction of the place's leaflet.
    const double place = kA2PerUm2 / (static_cast<double>(patch.period_x) * patch.period_y);
    const bool outer = l.position.z >= 0.f;
    requested[l.type] += place * (1.0 - (outer ? mixed.outer : mixed.inner));
    for (const LipidSpecies& species : patch.mix)
      requested[species.conformers.front().type] += place * (outer ? species.outer : species.inner);
    const glm::quat q = glm::normalize(l.rotation);
    const glm::vec3 up = glm::conjugate(q) * glm::vec3(0.f, 0.f, 1.f);  // the normal in the lipid's frame
    band = std::max(band, p.shapes[l.type].radius_about_axis(up) * 1.0001f);
    largest = std::max(largest, p.shapes[l.type].radius());
    check_fits(p.what, p.types[l.type], band, p.edge);
  }
  for (const LipidSpecies& species : patch.mix)
    for (const Instance& c : species.conformers) {
      band = std::max(band, p.shapes[c.type].radius_about_axis(glm::vec3(0.f, 0.f, 1.f)) * 1.0001f);
      largest = std::max(largest, p.shapes[c.type].radius());
      check_fits(p.what, p.types[c.type], band, p.edge);
    }
  return largest;
}

// A copy and its periodic images one edge away, so that the tile's edges are checked too; returns
// their ids in `n`.
std::array<std::size_t, 9> add_with_images(CopyNeighbourhood& n, const Instance& c, float edge) {
  std::array<std::size_t, 9> ids{};
  const glm::mat3 rotation = glm::mat3_cast(c.rotation);
  int k = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) ids[k++] = n.add(c.type, {c.position + edge * glm::vec3(dx, dy, 0), rotation});
  return ids;
}

bool collides(const CopyNeighbourhood& n, const Instance& c, const ClashRule& rule) {
  return n.collides(c.type, {c.position, glm::mat3_cast(c.rotation)}, rule);
}

// The base patch, repeated and rescaled, minus the lipids that then clash (in patch order).
std::vector<Instance> repeat_patch(const PatchLaying& p, float largest) {
  const LipidPatch& patch = p.patch;
  const float period[2] = {patch.period_x, patch.period_y};
  int repeats[2];
  float scale[2];
  for (int a = 0; a < 2; ++a) {
    repeats[a] = std::max(1, static_cast<int>(std::lround(p.edge / period[a])));
    scale[a] = p.edge / (static_cast<float>(repeats[a]) * period[a]);
  }
  std::vector<Instance> copies;
  CopyNeighbourhood kept(p.shapes, 2.f * largest);
  for (int j = 0; j < repeats[1]; ++j)
    for (int i = 0; i < repeats[0]; ++i)
      for (const Instance& l : patch.lipids) {
        Instance copy = l;
        copy.rotation = glm::normalize(l.rotation);
        const int cell[2] = {i, j};
        for (int a = 0; a < 2; ++a) {
          double x = std::fmod(static_cast<double>(l.position[a]), static_cast<double>(period[a]));
          if (x < 0.0) x += period[a];
          copy.position[a] = static_cast<float>((x + cell[a] * static_cast<double>(period[a])) * scale[a]);
          if (!(copy.position[a] < p.edge)) copy.position[a] = 0.f;  // rounded onto the edge: its periodic twin
        }
        if (collides(kept, copy, p.rule)) continue;
        add_with_images(kept, copy, p.edge);
        copies.push_back(copy);
      }
  return copies;
}

struct Candidate {
  double score;
  Instance copy;
};

// Candidates for a place, best first: conformers of the species from the same leaflet at kSpins
// turns, scored by how far their atoms stand from the base lipid's (the room that lipid proved
// free): the closest shape is the likeliest to fit.
std::vector<Candidate> ranked_conformers(const Instance& place, const LipidSpecies& species,
                                         const std::vector<CollisionShape>& shapes) {
  const glm::mat3 base_rotation = glm::mat3_cast(place.rotation);
  std::vector<glm::vec3> base;
  for (const AtomSphere& a : shapes[place.type].atoms()) base.push_back(place.position + base_rotation * a.centre);
  std::vector<Candidate> out;
  for (const Instance& conformer : species.conformers) {
    if ((conformer.position.z >= 0.f) != (place.position.z >= 0.f)) continue;
    for (int k = 0; k < kSpins; ++k) {
      Instance c = conformer;
      c.position = glm::vec3(place.position.x, place.position.y, conformer.position.z);
      c.rotation = glm::normalize(spin_about_z(static_cast<float>(2.0 * M_PI * k / kSpins)) * conformer.rotation);
      const glm::mat3 r = glm::mat3_cast(c.rotation);
      double score = 0.0;
      for (const AtomSphere& a : shapes[c.type].atoms()) {
        const glm::vec3 pos = c.position + r * a.centre;
        float nearest = INFINITY;
        for (const glm::vec3& b : base) nearest = std::min(nearest, glm::dot(pos - b, pos - b));
        score += std::sqrt(static_cast<double>(nearest));
      }
      out.push_back({score / static_cast<double>(shapes[c.type].atoms().size()), c});
    }
  }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  if (out.size() > static_cast<std::size_t>(kMixAttempts)) out.resize(kMixAttempts);
  return out;
}

// The mix: each species takes its fraction of each leaflet's places, tried in a random order, each
// place taking the first of its conformers (same leaflet, turned about the normal) that fits among
// all the others: places where the species fits are found until the leaflet holds its share.
// Every place starts with its base lipid, and a place is given to a species only when a conformer
// fits among everything standing then, its own base lipid set aside: a conformer never takes room
// a neighbour's base lipid still needs, so a place where none fits keeps its base lipid, and mixing
// opens no hole.
class PatchMixer {
public:
  PatchMixer(const PatchLaying& p, float largest, std::vector<Instance>& places)
      : p_(p), places_(places), standing_(places.size()), mixed_(p.shapes, 2.f * largest) {
    for (std::size_t i = 0; i < places_.size(); ++i) standing_[i] = add_with_images(mixed_, places_[i], p_.edge);
  }

  // Whether place i now holds a conformer of the species, trying `candidates` (ranked_conformers of
  // the place's base lipid) in their order.
  bool try_species(std::size_t i, const std::vector<Candidate>& candidates) {
    Instance& place = places_[i];
    for (const std::size_t id : standing_[i]) mixed_.retire(id);
    bool fitted = false;
    for (std::size_t k = 0; k < candidates.size() && !fitted; ++k) {
      // The best-ranked shapes also nudged a little: equilibrated neighbours leave no room to spare.
      const int nudges = k < kNudgedCandidates ? 5 : 1;
      for (int n = 0; n < nudges && !fitted; ++n) {
        Instance c = candidates[k].copy;
        if (n > 0) c.position += kNudge * glm::vec3(n == 1 ? 1.f : n == 2 ? -1.f : 0.f, n == 3 ? 1.f : n == 4 ? -1.f : 0.f, 0.f);
        if (collides(mixed_, c, p_.rule)) continue;
        place = c;
        fitted = true;
      }
    }
    standing_[i] = add_with_images(mixed_, place, p_.edge);  // the conformer, or the base lipid back
    return fitted;
  }

private:
  const PatchLaying& p_;
  std::vector<Instance>& places_;
  std::vector<std::array<std::size_t, 9>> standing_;  // per place, the ids of it and its images
  CopyNeighbourhood mixed_;
};

// The conformers ranked for the places a leaflet's mixing tries, in its order. A place is tried
// holding its base lipid (a place that takes no conformer gets it back), so its ranking depends on
// nothing the mixing changes, and the next kRankedAhead places are ranked at once, on every job.
class RankedAhead {
public:
  RankedAhead(const PatchLaying& p, const LipidSpecies& species, const std::vector<Instance>& places,
              const std::vector<std::size_t>& to_try, int threads)
      : p_(p), species_(species), places_(places), to_try_(to_try), threads_(threads) {}

  // The ranking of to_try[k]; k only grows from one call to the next.
  const std::vector<Candidate>& at(std::size_t k) {
    if (k >= first_ + batch_.size()) {
      first_ = k;
      batch_.assign(std::min(to_try_.size() - k, kRankedAhead), {});
      parallel_for(batch_.size(), threads_,
                   [&](std::size_t i) { batch_[i] = ranked_conformers(places_[to_try_[first_ + i]], species_, p_.shapes); });
    }
    return batch_[k - first_];
  }

private:
  static constexpr std::size_t kRankedAhead = 32;
  const PatchLaying& p_;
  const LipidSpecies& species_;
  const std::vector<Instance>& places_;
  const std::vector<std::size_t>& to_try_;
  int threads_;
  std::size_t first_ = 0;
  std::vector<std::vector<Candidate>> batch_;
};

// Gives each mixed species its share of each leaflet's places; returns per place whether a species took it.
std::vector<char> mix_species(const PatchLaying& p, float largest, uint64_t seed, int threads, std::vector<Instance>& places) {
  SplitMix64 rng(mix64(seed ^ 0x11D1DC0FFEEull));
  PatchMixer mixer(p, largest, places);
  std::vector<char> taken(places.size(), 0);
  std::vector<std::size_t> order(places.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.below(static_cast<uint32_t>(i))]);
  for (const LipidSpecies& species : p.patch.mix)
    for (const bool outer : {true, false}) {
      std::size_t leaflet_places = 0;
      for (const Instance& c : places) leaflet_places += (c.position.z >= 0.f) == outer;
      std::size_t wanted = static_cast<std::size_t>(std::lround((outer ? species.outer : species.inner) * double(leaflet_places)));
      std::vector<std::size_t> to_try;  // in order: only the place being tried can be taken before its turn
      for (const std::size_t i : order)
        if (!taken[i] && (places[i].position.z >= 0.f) == outer) to_try.push_back(i);
      RankedAhead ranked(p, species, places, to_try, threads);
      for (std::size_t k = 0; k < to_try.size() && wanted > 0; ++k)
        if (mixer.try_species(to_try[k], ranked.at(k))) {
          taken[to_try[k]] = 1;
          --wanted;
        }
    }
  return taken;
}

// A conformer of another species fits its place in the flat patch with no room to spare, and the
// surface's compression (the inner leaflet, a chart's corners) can push it into a neighbour: the
// place's base lipid, which proved the room free in an equilibrated patch, stays behind as its
// alternate, shown by the pruning where the conformer had to go.
void keep_base_lipids_as_alternates(const std::vector<Instance>& base_lipids, const std::vector<char>& taken,
                                    FixedLayer& layer) {
  for (std::size_t i = 0; i < taken.size(); ++i)
    if (taken[i]) {
      layer.copies[i].has_alternate = true;
      Instance alternate = base_lipids[i];
      alternate.alternate = true;
      layer.copies.push_back(alternate);
    }
}

// Where the real surface pushes a lipid into a clash (across a UV seam, where a cube-sphere corner
// squeezes tile space, beside a protein the curvature turns), the same lipid a hair aside or turned
// about the normal often fits. A membrane pruned on its whole surface keeps these as alternates of
// each layer lipid, shown only where the lipid itself was dropped (shell/membrane_pruning.hpp). On
// the virion, 1 Å four ways and a half turn take the worst frontal view from 98.7 % to 99.4 % of
// its pixels (2 Å: 99.2 %, 3 Å: 99.1 %; eight ways: 99.5 % for a third more copies to check).
constexpr float kAsideShift = 1.f;  // Å, in tile space
constexpr int kAsideDirections = 4;
static_assert(kAsideDirections + 1 == kAlternatesPerLaidLipid, "four ways aside and one half turn");

void add_lipids_aside_as_alternates(FixedLayer& layer) {
  const std::size_t lipids = layer.copies.size();
  const auto add = [&](Instance copy) {
    copy.alternate = true;
    copy.has_alternate = false;
    layer.copies.push_back(copy);
  };
  for (std::size_t i = 0; i < lipids; ++i) {
    const Instance lipid = layer.copies[i];
    if (lipid.alternate) continue;
    for (int k = 0; k < kAsideDirections; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / kAsideDirections;
      Instance aside = lipid;
      aside.position += kAsideShift * glm::vec3(float(std::cos(angle)), float(std::sin(angle)), 0.f);
      add(aside);
    }
    Instance turned = lipid;
    turned.rotation = glm::angleAxis(float(std::numbers::pi), glm::vec3(0.f, 0.f, 1.f)) * lipid.rotation;
    add(turned);
  }
}

// One kind per molecule name: the conformers of a lipid share their kind's name.
std::vector<uint32_t> kinds_by_name(const std::vector<MoleculeType>& types) {
  std::map<std::string, uint32_t> kind;
  std::vector<uint32_t> kinds;
  kinds.reserve(types.size());
  for (const MoleculeType& t : types) kinds.push_back(kind.emplace(t.name, static_cast<uint32_t>(kind.size())).first->second);
  return kinds;
}

// The patch repeated over one tile with centres rescaled to the tile edge, minus the lipids that
// clash with kept ones (in patch order) or with their images one edge away.
FixedLayer lay_patch(const char* what, const LipidPatch& patch, float edge, const std::vector<MoleculeType>& types,
                     const std::vector<CollisionShape>& shapes, SurfaceDistortion surface, uint64_t seed, int threads,
                     std::vector<double>& requested) {
  const PatchLaying p{what, patch, edge, types, shapes, ClashRule{patch.clearance, surface}};
  requested.assign(types.size(), 0.0);
  const LeafletShares mixed = check_patch(p);
  FixedLayer layer;
  layer.clearance = patch.clearance;
  const float largest = request_places(p, mixed, layer.band, requested);
  layer.copies = repeat_patch(p, largest);
  layer.kind_of_type = kinds_by_name(types);
  layer.refused_stay_as_alternates = surface.rigid();
  // Only a membrane pruned on its whole surface (tiles packed rigid) can pick alternates.
  if (!patch.mix.empty()) {
    const std::vector<Instance> base_lipids = surface.rigid() ? layer.copies : std::vector<Instance>{};
    const std::vector<char> taken = mix_species(p, largest, seed, threads, layer.copies);
    if (!base_lipids.empty()) keep_base_lipids_as_alternates(base_lipids, taken, layer);
  }
  if (surface.rigid()) add_lipids_aside_as_alternates(layer);
  return layer;
}

}  // namespace

double copies_per_um3_from_millimolar(double millimolar) { return millimolar * 1e-3 * kAvogadro / 1e27 * kA3PerUm3; }

WangSet make_membrane_tiles(const MembraneTileRequest& r) {
  const char* what = "membrane tiles";
  check_common(what, r.edge, r.types, r.budget);
  for (const float v : {r.surface.lateral_stretch, r.surface.curvature, r.surface.tilt, r.surface.max_rise})
    if (!(v >= 0.f) || !std::isfinite(v))
      throw InputError(what, "surface", "chart stretch, curvature and normal tilt to pack for must be finite numbers >= 0");
  const SurfaceDistortion& surface = r.surface;
  const std::vector<CollisionShape> shapes = shapes_of(r.types);
  const glm::vec3 z(0.f, 0.f, 1.f);
  std::vector<Wanted> wanted;
  for (const MembraneMolecule& m : r.molecules) {
    check_type(what, r.types, m.type, m.copies_per_um2);
    if (!std::isfinite(m.depth)) throw InputError(what, r.types[m.type].name, "depth must be finite");
    PlacementSpec s;
    s.type = m.type;
    s.copies_per_volume = m.copies_per_um2 / kA2PerUm2;
    s.band = shapes[m.type].radius_about_axis(r.types[m.type].up_axis) * 1.0001f;
    s.base = rotation_between(r.types[m.type].up_axis, z);
    s.z = m.depth;
    check_fits(what, r.types[m.type], s.band, r.edge);
    wanted.push_back({s, m.copies_per_um2, true});
  }
  if (r.lipids) {
    const LipidFill& l = *r.lipids;
    check_type(what, r.types, l.type, 1.0);
    if (!(l.area_per_lipid > 0.f) || !std::isfinite(l.leaflet_offset))
      throw InputError(what, "lipids", "area per lipid must be > 0 and the leaflet offset finite");
    const glm::vec3 up = r.types[l.type].up_axis;
    PlacementSpec upper;
    upper.type = l.type;
    upper.copies_per_volume = 1.0 / l.area_per_lipid;
    upper.band = shapes[l.type].radius_about_axis(up) * 1.0001f;
    upper.base = rotation_between(up, z);
    upper.z = l.leaflet_offset;
    upper.densify = false;  // fills what room is left; not worth shaking thousands of copies for
    check_fits(what, r.types[l.type], upper.band, r.edge);
    PlacementSpec lower = upper;
    lower.base = rotation_between(up, -z);
    lower.z = -l.leaflet_offset;
    const double per_um2 = kA2PerUm2 / l.area_per_lipid;
    wanted.push_back({upper, per_um2, false});
    wanted.push_back({lower, per_um2, false});
  }
  FixedLayer layer;
  std::vector<double> layer_requested;
  if (r.lipid_patch) {
    if (r.lipids) throw InputError(what, "lipids", "give either a lipid fill or a lipid patch, not both");
    layer = lay_patch(what, *r.lipid_patch, r.edge, r.types, shapes, surface, r.seed, r.budget.threads, layer_requested);
    for (const MembraneMolecule& m : r.molecules)
      if (m.lipids_displaced_on_surface) layer.laid_through.push_back(m.type);
  }
  return pack(what, 2, r.edge, make_complete_colouring(2, r.colours), r.types, shapes, wanted, r.seed, r.budget,
              surface, layer, layer_requested);
}

WangSet make_soluble_cubes(const SolubleCubeRequest& r) {
  const char* what = "soluble cubes";
  check_common(what, r.edge, r.types, r.budget);
  if (r.variants < 0) throw InputError(what, "variants", "variants must be >= 0 (0 = complete set)");
  const std::vector<CollisionShape> shapes = shapes_of(r.types);
  std::vector<Wanted> wanted;
  for (const SolubleMolecule& m : r.molecules) {
    check_type(what, r.types, m.type, m.copies_per_um3);
    PlacementSpec s;
    s.type = m.type;
    s.copies_per_volume = m.copies_per_um3 / kA3PerUm3;
    s.band = shapes[m.type].radius() * 1.0001f;
    s.uniform_rotation = true;
    check_fits(what, r.types[m.type], s.band, r.edge);
    wanted.push_back({s, m.copies_per_um3, true});
  }
  const WangColouring colouring = r.variants == 0 ? make_complete_colouring(3, r.colours)
                                                  : make_variant_colouring(3, r.colours, r.variants, r.seed);
  return pack(what, 3, r.edge, colouring, r.types, shapes, wanted, r.seed, r.budget);
}

float WangSet::max_overhang() const {
  float over = 0.f;
  for (const WangTile& t : tiles) {
    if (t.instances.empty()) continue;
    for (int a = 0; a < dims; ++a) over = std::max({over, -t.atoms_min[a], t.atoms_max[a] - edge});
  }
  return over;
}

}  // namespace nano::tiles
