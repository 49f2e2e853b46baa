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

// True when two copies have atoms closer than clearance * (sum of radii).
bool copies_collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                    float clearance);

}  // namespace nano::tiles
