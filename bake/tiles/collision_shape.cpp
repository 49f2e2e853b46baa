#include "bake/tiles/collision_shape.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>

namespace nano::tiles {

CollisionShape::CollisionShape(const MoleculeType& type) {
  if (type.atoms.empty()) throw InputError(type.name, "atoms", "molecule type has no atoms");
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const AtomSphere& a : type.atoms) {
    if (!(a.radius > 0.f) || !std::isfinite(a.radius) || !std::isfinite(a.centre.x) ||
        !std::isfinite(a.centre.y) || !std::isfinite(a.centre.z))
      throw InputError(type.name, "atoms", "every atom needs a finite centre and a positive radius");
    lo = glm::min(lo, a.centre);
    hi = glm::max(hi, a.centre);
    radius_ = std::max(radius_, glm::length(a.centre) + a.radius);
    max_atom_radius_ = std::max(max_atom_radius_, a.radius);
  }
  // Cells of one atom diameter: a query then spans at most 3 cells per axis.
  cell_ = 2.f * max_atom_radius_;
  grid_min_ = lo;
  dims_ = glm::max(glm::ivec3(glm::floor((hi - lo) / cell_)) + 1, glm::ivec3(1));
  const auto cell_of = [&](const glm::vec3& c) {
    const glm::ivec3 g = glm::clamp(glm::ivec3(glm::floor((c - grid_min_) / cell_)), glm::ivec3(0), dims_ - 1);
    return static_cast<uint32_t>((g.z * dims_.y + g.y) * dims_.x + g.x);
  };
  const size_t cells = static_cast<size_t>(dims_.x) * dims_.y * dims_.z;
  cell_start_.assign(cells + 1, 0);
  for (const AtomSphere& a : type.atoms) ++cell_start_[cell_of(a.centre) + 1];
  for (size_t i = 0; i < cells; ++i) cell_start_[i + 1] += cell_start_[i];
  atoms_.resize(type.atoms.size());
  std::vector<uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (const AtomSphere& a : type.atoms) atoms_[fill[cell_of(a.centre)]++] = a;
}

float CollisionShape::radius_about_axis(glm::vec3 axis) const {
  axis = glm::normalize(axis);
  float r = 0.f;
  for (const AtomSphere& a : atoms_) {
    const glm::vec3 off = a.centre - glm::dot(a.centre, axis) * axis;
    r = std::max(r, glm::length(off) + a.radius);
  }
  return r;
}

bool CollisionShape::touches(glm::vec3 point, float radius, float clearance) const {
  const float reach = clearance * (radius + max_atom_radius_);
  const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor((point - reach - grid_min_) / cell_)), glm::ivec3(0));
  const glm::ivec3 hi = glm::min(glm::ivec3(glm::floor((point + reach - grid_min_) / cell_)), dims_ - 1);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const size_t c = (static_cast<size_t>(z) * dims_.y + y) * dims_.x + x;
        for (uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
          const AtomSphere& a = atoms_[i];
          const float limit = clearance * (radius + a.radius);
          const glm::vec3 d = point - a.centre;
          if (glm::dot(d, d) < limit * limit) return true;
        }
      }
  return false;
}

bool copies_collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                    const ClashRule& rule) {
  const glm::vec3 between = pa.position - pb.position;
  const float reach = a.radius() + b.radius();
  if (glm::dot(between, between) >= reach * reach) return false;
  const glm::vec3 spread = 0.5f * rule.lateral_stretch * glm::vec3(-between.x, -between.y, 0.f);
  const float widen = glm::length(spread);
  const glm::vec3 b_position = pb.position + spread;
  // Walk the copy with fewer atoms, expressed in the other copy's frame.
  const bool swap = a.atoms().size() > b.atoms().size();
  const CollisionShape& walk = swap ? b : a;
  const CollisionShape& grid = swap ? a : b;
  const Pose& pw = swap ? pb : pa;
  const Pose& pg = swap ? pa : pb;
  const glm::vec3 walk_position = swap ? b_position : pa.position;
  const glm::vec3 grid_position = swap ? pa.position : b_position;
  const glm::mat3 to_grid = glm::transpose(pg.rotation) * pw.rotation;
  const glm::vec3 shift = glm::transpose(pg.rotation) * (walk_position - grid_position);
  const float outer = grid.radius();
  for (const AtomSphere& atom : walk.atoms()) {
    const glm::vec3 q = to_grid * atom.centre + shift;
    // |atom centre in grid| + clearance * (r + r_grid) + widen, bounded with |centre| <= outer − r_grid.
    const float lim =
        outer + atom.radius + widen + std::max(0.f, rule.clearance - 1.f) * (atom.radius + grid.max_atom_radius());
    if (glm::dot(q, q) >= lim * lim) continue;
    if (grid.touches(q, atom.radius + widen / rule.clearance, rule.clearance)) return true;
  }
  return false;
}

}  // namespace nano::tiles
