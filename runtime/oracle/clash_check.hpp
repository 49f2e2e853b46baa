#pragma once
// Clash checker for exported atoms: pairs of atoms of DIFFERENT copies whose centres are closer
// than factor × (r1 + r2). Two atoms of one copy are the molecule's own business (bonded atoms
// overlap by design); atoms of different copies should not interpenetrate that deeply.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace nano::oracle {

struct ClashAtom {
  std::uint64_t copy = 0;  // Copy::number
  glm::dvec3 position{0.0};
  double radius = 0.0;
};

struct Clash {
  std::size_t a = 0, b = 0;  // indices into the checked atoms, a < b
  double distance = 0;
  double limit = 0;          // factor × (r_a + r_b)
};

struct ClashReport {
  std::uint64_t count = 0;      // every clashing pair
  std::vector<Clash> pairs;     // up to max_pairs of them (lowest a first), sorted by (a, b)
};

inline constexpr double kClashFactor = 0.6;

// Grid hash with cells of factor × 2 × the largest radius, so every clashing pair lies in the
// same or adjacent cells: O(n) for atoms of bounded density. Throws std::invalid_argument for a
// negative or non-finite factor, radius or coordinate.
ClashReport find_clashes(std::span<const ClashAtom> atoms, double factor = kClashFactor, std::size_t max_pairs = 1000);

}  // namespace nano::oracle
