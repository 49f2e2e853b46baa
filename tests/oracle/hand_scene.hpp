#pragma once
// Hand-built packages whose every atom position follows from plane geometry, and the analytic
// oracle of those positions (double precision, glm::dquat rotations, no shared placement code).
//
// Membrane compartments: the square [0, L]² in the z = 0 plane, split along its diagonal into two
// triangles that share the edge (0,0)-(L,L), vertex normals +z, UV scale k = 64 Å/UV, Wang squares
// S = 32 Å (s = 1/2 UV, 4 × 4 cells over the square). UV = (x, y)/k, or ((L − x), y)/k for the
// mirrored chart. A molecule at tile position (x, y, z) in cell (a, b) sits at UV
// (a·s + x/k, b·s + y/k); the square owns it iff u ∈ (0, 2] and v ∈ [0, 2) (ownership.h's global
// tie rule p + (−ε², ε) on the chart's outer boundary), and it lands at (k·u, k·v, z) (mirrored:
// (L − k·u, k·v, z), rotated by 180° about z so it stays proper).
// Core compartment: a 3 × 2 × 2 grid of 20 Å boxes with INSIDE / OUTSIDE / BOUNDARY boxes and a
// 2 × 1 × 1 recipe that wraps along every axis.
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "tests/format/sample_scene.hpp"

namespace nano::explicit_test {

using format::test::SampleScene;

inline constexpr double kK = 64, kS = 32, kL = 128, kBox = 20;

// One atom of the analytic oracle, keyed the way the oracle names copies.
struct AtomKey {
  std::uint32_t compartment_instance;
  int kind;  // 0 membrane, 1 core
  glm::ivec3 cell;
  std::uint32_t instance;
  std::uint32_t atom;
  auto tie() const { return std::tie(compartment_instance, kind, cell.x, cell.y, cell.z, instance, atom); }
  bool operator<(const AtomKey& o) const { return tie() < o.tie(); }
};
struct ExpectedAtom {
  glm::dvec3 position;
  double radius;
};
using Expected = std::map<AtomKey, ExpectedAtom>;

struct Placement {  // a compartment instance: compartment, rotation (axis, degrees), translation
  std::uint32_t compartment;
  glm::dvec3 axis{0, 0, 1};
  double degrees = 0;
  glm::dvec3 translation{0.0};
};

// Compartments: 0 = flat membrane, 1 = mirrored flat membrane, 2 = core grid only.
// The default placements put one instance of each, the flat one twice (once rotated and moved).
std::vector<Placement> default_placements();
SampleScene hand_scene(const std::vector<Placement>& placements = default_placements());

// Every atom of every copy the scene holds, from plane geometry.
Expected expected_atoms(const SampleScene& scene, const std::vector<Placement>& placements = default_placements());

}  // namespace nano::explicit_test
