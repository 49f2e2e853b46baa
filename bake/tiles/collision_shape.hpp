#pragma once
// Atom-level collision test between two rigid copies of molecules: each type keeps its atoms in a
// dense local grid, so a pair test visits only the atoms of one copy that lie inside the other's
// bounding sphere, and only the grid cells around each of them. The walked copy goes block by block
// (atoms of a coarser grid, each with a bounding sphere), so whole blocks that cannot reach the
// other copy's atoms are passed over without transforming their atoms.
#include "bake/tiles/molecule_type.hpp"

#include <glm/glm.hpp>

#include <algorithm>

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

  // Atoms of a coarse grid cell, bounded by a sphere about `centre` (atom centres within `spread`).
  struct Block {
    glm::vec3 centre{0.f};
    float spread = 0.f;
    float max_atom_radius = 0.f;
    uint32_t begin = 0, end = 0;  // range of block_atoms()
  };
  const std::vector<Block>& blocks() const { return blocks_; }
  const std::vector<AtomSphere>& block_atoms() const { return block_atoms_; }
  // The box of the atom centres (local frame): touches is false `reach` beyond it.
  glm::vec3 centre_min() const { return grid_min_; }
  glm::vec3 centre_max() const { return centre_max_; }

private:
  std::vector<AtomSphere> atoms_;  // sorted by grid cell
  std::vector<uint32_t> cell_start_;
  std::vector<Block> blocks_;
  std::vector<AtomSphere> block_atoms_;  // the atoms again, sorted by block
  glm::vec3 grid_min_{0.f}, centre_max_{0.f};
  glm::ivec3 dims_{1};
  float cell_ = 1.f, radius_ = 0.f, max_atom_radius_ = 0.f;
};

// When two copies clash. Copies of a membrane tile reach the surface through the chart, whose
// in-plane map is (after the frame turn) a symmetric stretch P with eigenvalues in [1, 1 + e]
// (e = lateral_stretch): tile-space centre offset p becomes P·p_xy + p_z, atom offsets stay rigid.
// On a curved surface the normals turn by up to κ (curvature, rad/Å) per Å, so what stands h Å
// from the surface sees lateral offsets scaled by a factor in [1 − κh, 1 + κh] (spread on the
// convex side, squeezed on the concave one): for a pair whose atoms reach H from the surface, the
// eigenvalues lie in [lo, hi] with lo = 1 − κ·H and hi = (1 + e)(1 + κ·H). With A = P − I, A·p_xy
// lies in the ball centred m·p_xy of radius w·|p_xy|, m = (lo + hi)/2 − 1, w = (hi − lo)/2.
// Copies stand along interpolated normals up to an angle θ from their flat triangle
// (tilt = tan θ), so a neighbour p_xy away also rises or sinks by up to tilt·|p_xy| in the copy's
// frame, and by no more than max_rise however far apart (an estimate: the facets' sag from the
// smooth surface their corner normals describe; the bake tests check the bundled scenes by explicit
// instancing). Testing copy b shifted by m·p_xy and by −⅔, 0, +⅔ of that rise along z, with the
// clearance widened by w·|p_xy| + ⅓ of the rise, covers every such deformation. e = κ = tilt = 0
// is the plain rigid test; cubes (no chart) always use it.

// What the meshes that wear a membrane do to its tiles, all >= 0 (zero: a flat, faithful chart).
struct SurfaceDistortion {
  float lateral_stretch = 0.f;  // e: the chart's largest stretch beyond 1 (tile-space x and y)
  float curvature = 0.f;        // κ, rad per Å; heights are tile-space z ± the copy's radius
  float tilt = 0.f;             // tan of the largest angle between an interpolated and a face normal
  float max_rise = 0.f;         // Å: the tilt's rise never exceeds this (the facets' sag); 0 = no rise

  // Nothing to survive: tiles packed rigid, whose copies the baker checks on the real surface.
  bool rigid() const { return lateral_stretch == 0.f && curvature == 0.f && tilt == 0.f; }
};

struct ClashRule {
  float clearance = 1.f;  // atoms of different copies stay >= clearance * (sum of radii) apart
  SurfaceDistortion surface;

  // The smallest factor a lateral offset can shrink by for copies reaching `height` Å from the
  // surface (1 − κ·height, kept >= 1/2): bounding spheres further apart than (r_a + r_b) / it
  // cannot clash, so neighbour searches widen by its inverse.
  float closest_scale(float height) const { return std::max(0.5f, 1.f - surface.curvature * height); }
};

// True when two copies have atoms closer than the rule allows; false whenever their bounding
// spheres are further apart than (r_a + r_b) / closest_scale.
bool copies_collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                    const ClashRule& rule);

}  // namespace nano::tiles
