#pragma once
// Atom-level collision test between two rigid copies of molecules: each type keeps its atoms in a
// dense local grid, so a pair test visits only the atoms of one copy that lie inside the other's
// bounding sphere, and only the grid cells around each of them.
#include "bake/tiles/molecule_type.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace nano::tiles {

struct Pose {
  glm::vec3 position{0.f};
  glm::mat3 rotation{1.f};
};

class CollisionShape {
public:
  // Throws InputError for a type without atoms or with a non-positive or non-finite radius.
  explicit CollisionShape(const MoleculeType& type);

  const std::vector<AtomSphere>& atoms() const { return atoms_; }
  float radius() const { return radius_; }  // max over atoms of |centre| + radius, about the origin
  float max_atom_radius() const { return max_atom_radius_; }
  // Largest distance of an atom surface from the line through the origin along `axis` (unit):
  // the extent in the membrane plane of a copy standing along `axis`, whatever its spin.
  float radius_about_axis(glm::vec3 axis) const;
  // True when some atom is closer to `point` (local frame) than clearance * (radius + atom radius).
  bool touches(glm::vec3 point, float radius, float clearance) const;

private:
  std::vector<AtomSphere> atoms_;  // sorted by grid cell
  std::vector<uint32_t> cell_start_;
  glm::vec3 grid_min_{0.f};
  glm::ivec3 dims_{1};
  float cell_ = 1.f, radius_ = 0.f, max_atom_radius_ = 0.f;
};

// When two copies clash. Copies of a membrane tile reach the surface through the chart, whose
// in-plane map is (after the frame turn) a symmetric stretch P with eigenvalues in [1, 1 + e]
// (e = lateral_stretch): tile-space centre offset p becomes P·p_xy + p_z, atom offsets stay rigid.
// With A = P − I (0 ≼ A ≼ e·I), A·p_xy lies in the ball centred e·p_xy/2 of radius e·|p_xy|/2, so
// testing copy b shifted by e·p_xy/2 with the clearance widened by e·|p_xy|/2 covers every such P
// at once. e = 0 is the plain rigid test; cubes (no chart) always use 0.
struct ClashRule {
  float clearance = 1.f;       // atoms of different copies stay >= clearance * (sum of radii) apart
  float lateral_stretch = 0.f;  // e >= 0, tile-space x and y only
};

// True when two copies have atoms closer than the rule allows. Never true for copies whose
// bounding spheres are apart: P only spreads centres, so a stretch cannot bring spheres closer.
bool copies_collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                    const ClashRule& rule);

}  // namespace nano::tiles
