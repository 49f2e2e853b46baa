#include "bake/scene/random_placement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "common/error.hpp"

namespace nano::scene {
namespace {

// splitmix64 (Steele, Lea, Flood 2014): tiny, fast, and defined bit for bit, unlike the
// standard library's distributions.
class SplitMix64 {
public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1): the top 53 bits as a double.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

private:
  std::uint64_t state_;
};

// Uniform over rotations (Shoemake, Graphics Gems III, 1992); returned as (w, x, y, z).
glm::dvec4 random_unit_quaternion(SplitMix64& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
  return {b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3)};
}

struct Sphere {
  glm::dvec3 centre;
  double radius;
};

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The spheres placed so far, found by grids, so that a placement of n copies costs O(n), not
// O(n^2) (10^6 copies: seconds, not hours). Spheres of different sizes would defeat one grid (a
// cell as wide as a cell body holds thousands of virions), so each power of two of the radius has
// its own level, whose cells are as wide as its spheres plus the widest min_gap they are placed
// with. A query looks at the cells of each level that the candidate can reach, or, when those are
// more than the level's spheres, at its spheres one by one; a level whose spheres all lie out of
// reach is skipped at once. Answers exactly what testing every sphere would.
class PlacedSpheres {
public:
  // `cell_for(level)`: the cell width of each level that random copies are placed in.
  explicit PlacedSpheres(std::unordered_map<int, double> cell_for) : cell_for_(std::move(cell_for)) {}

  // Radius in [2^(k-1), 2^k): level k. (ilogb of 0, an infinity or NaN is INT_MIN or INT_MAX.)
  static int level_of(double radius) { return std::clamp(std::ilogb(radius), -1075, 1023) + 1; }

  void add(const Sphere& s) {
    const int k = level_of(s.radius);
    auto it = levels_.find(k);
    if (it == levels_.end()) {
      const auto cell = cell_for_.find(k);
      it = levels_.emplace(k, Level(cell != cell_for_.end() ? cell->second : 2.0 * std::ldexp(1.0, k))).first;
    }
    it->second.add(s);
  }

  bool clear_of_all(const Sphere& candidate, double gap) const {
    for (const auto& [k, level] : levels_)
      if (!level.clear_of_all(candidate, gap)) return false;
    return true;
  }

private:
  class Level {
  public:
    explicit Level(double cell) : cell_(cell) {}

    void add(const Sphere& s) {
      if (all_.empty()) lo_ = hi_ = s.centre;
      lo_ = glm::min(lo_, s.centre);
      hi_ = glm::max(hi_, s.centre);
      largest_ = std::max(largest_, s.radius);
      const glm::dvec3 k = cell_of(s.centre);
      cells_[key(k.x, k.y, k.z)].push_back(static_cast<std::uint32_t>(all_.size()));
      all_.push_back(s);
    }

    bool clear_of_all(const Sphere& candidate, double gap) const {
      const auto clear = [&](const Sphere& s) {
        return glm::distance(s.centre, candidate.centre) >= s.radius + candidate.radius + gap;
      };
      // Every sphere the candidate can touch has its centre within `reach` of the candidate's
      // (a hair more, so that rounding never leaves one out).
      const double sum = candidate.radius + largest_ + gap;
      const double reach = sum + 1e-9 * (sum + glm::length(candidate.centre));
      const glm::dvec3 from = glm::max(candidate.centre - reach, lo_), to = glm::min(candidate.centre + reach, hi_);
      if (from.x > to.x || from.y > to.y || from.z > to.z) return true;  // all out of reach
      const glm::dvec3 lo = cell_of(from), hi = cell_of(to);
      const glm::dvec3 span = hi - lo + 1.0;
      if (span.x * span.y * span.z > static_cast<double>(all_.size())) {
        for (const Sphere& s : all_)
          if (!clear(s)) return false;
        return true;
      }
      for (double z = lo.z; z <= hi.z; ++z)
        for (double y = lo.y; y <= hi.y; ++y)
          for (double x = lo.x; x <= hi.x; ++x) {
            const auto it = cells_.find(key(x, y, z));
            if (it == cells_.end()) continue;
            for (const std::uint32_t i : it->second)
              if (!clear(all_[i])) return false;
          }
      return true;
    }

  private:
    // Cell coordinates, clamped far beyond any box a scene can hold a copy in.
    glm::dvec3 cell_of(const glm::dvec3& p) const {
      return glm::clamp(glm::floor(p / cell_), glm::dvec3(-kLimit), glm::dvec3(kLimit));
    }
    static std::uint64_t key(double x, double y, double z) {
      const auto part = [](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + kLimit) & 0x1FFFFF; };
      return part(x) | part(y) << 21 | part(z) << 42;
    }
    static constexpr double kLimit = 1 << 20;
    double cell_;
    double largest_ = 0.0;
    glm::dvec3 lo_{0.0}, hi_{0.0};  // bounds of the centres
    std::vector<Sphere> all_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
  };

  std::unordered_map<int, double> cell_for_;
  std::map<int, Level> levels_;
};

void place_copies(const RandomPlacement& entry, std::size_t entry_index, double radius,
                  const std::string& scene_file, PlacedSpheres& placed,
                  std::vector<PlacedInstance>& out) {
  const std::string where = "instances[" + std::to_string(entry_index) + "]";
  const glm::dvec3 lo = entry.box.min + radius, hi = entry.box.max - radius;
  if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z)
    throw InputError(scene_file, where,
                     "a bounding sphere of compartment \"" + entry.compartment.name + "\" (radius " + format(radius) +
                         " Å) does not fit inside the box; enlarge the box");
  SplitMix64 rng(entry.seed);
  for (int copy = 0; copy < entry.count; ++copy) {
    bool done = false;
    for (int attempt = 0; attempt < placement_attempts_per_copy && !done; ++attempt) {
      const glm::dvec3 u(rng.uniform(), rng.uniform(), rng.uniform());
      const Sphere candidate{lo + u * (hi - lo), radius};
      if (!placed.clear_of_all(candidate, entry.min_gap)) continue;
      placed.add(candidate);
      out.push_back({entry.compartment, rigid_transform(random_unit_quaternion(rng), candidate.centre)});
      done = true;
    }
    if (!done)
      throw InputError(scene_file, where,
                       "placed only " + std::to_string(copy) + " of " + std::to_string(entry.count) +
                           " copies of compartment \"" + entry.compartment.name + "\" (bounding radius " +
                           format(radius) + " Å, min_gap " + format(entry.min_gap) + " Å) without overlap; " +
                           std::to_string(placement_attempts_per_copy) +
                           " random positions for the next copy all collided. Enlarge the box, or lower count "
                           "or min_gap");
  }
}

}  // namespace

std::uint64_t derive_placement_seed(std::uint64_t scene_seed, std::size_t entry_index) {
  // One splitmix step from a state that mixes both inputs: distinct entries get unrelated streams.
  SplitMix64 mix(scene_seed ^ (0xD1B54A32D192ED03ull * (static_cast<std::uint64_t>(entry_index) + 1)));
  return mix.next();
}

std::size_t expanded_instance_count(const SceneDescription& scene) {
  std::size_t n = 0;
  for (const InstanceEntry& e : scene.instances)
    n += std::holds_alternative<RandomPlacement>(e) ? static_cast<std::size_t>(std::get<RandomPlacement>(e).count) : 1;
  return n;
}

std::vector<PlacedInstance> expand_random_instances(const SceneDescription& scene,
                                                    const std::vector<double>& bounding_radius) {
  // Invariants, not input: the baker measures every compartment's mesh, which the mesh checks have
  // already found closed, finite and of non-zero area.
  if (bounding_radius.size() != scene.compartments.size())
    throw std::invalid_argument("expand_random_instances: one bounding radius per compartment is needed");
  for (double r : bounding_radius)
    if (!(r > 0.0) || !std::isfinite(r))
      throw std::invalid_argument("expand_random_instances: bounding radii must be finite and > 0");

  const std::string scene_file = scene.source.string();
  // Each level's cells as wide as the largest sphere placed in it plus the widest gap it is placed
  // with: a candidate meets the spheres of its own level in at most the cells around its own.
  std::unordered_map<int, double> cell_for;
  for (const InstanceEntry& e : scene.instances)
    if (const auto* random = std::get_if<RandomPlacement>(&e)) {
      const double r = bounding_radius.at(random->compartment.index);
      double& cell = cell_for.try_emplace(PlacedSpheres::level_of(r), 0.0).first->second;
      cell = std::max({cell, 2.0 * std::ldexp(1.0, PlacedSpheres::level_of(r)), 2.0 * r + random->min_gap});
    }
  PlacedSpheres placed(std::move(cell_for));
  std::vector<PlacedInstance> out;
  out.reserve(expanded_instance_count(scene));
  // Explicit instances claim their space first, wherever they appear in the list, so a random
  // entry never lands on an explicit instance that happens to come later in the file.
  for (const InstanceEntry& e : scene.instances)
    if (const auto* fixed = std::get_if<ExplicitInstance>(&e))
      placed.add({transform_point(fixed->transform, glm::dvec3(0.0)),
                  bounding_radius.at(fixed->compartment.index) * largest_stretch(fixed->transform)});
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    if (const auto* fixed = std::get_if<ExplicitInstance>(&scene.instances[i]))
      out.push_back({fixed->compartment, fixed->transform});
    else {
      const auto& entry = std::get<RandomPlacement>(scene.instances[i]);
      place_copies(entry, i, bounding_radius.at(entry.compartment.index), scene_file, placed, out);
    }
  }
  return out;
}

}  // namespace nano::scene
