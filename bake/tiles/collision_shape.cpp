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

namespace {

// Atoms of a (at pa) against atoms of b placed at b_position: closer than clearance·(r1 + r2) + widen?
bool atoms_within(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                  const glm::vec3& b_position, float clearance, float widen) {
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
        outer + atom.radius + widen + std::max(0.f, clearance - 1.f) * (atom.radius + grid.max_atom_radius());
    if (glm::dot(q, q) >= lim * lim) continue;
    if (grid.touches(q, atom.radius + widen / clearance, clearance)) return true;
  }
  return false;
}

}  // namespace

bool copies_collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                    const ClashRule& rule) {
  const glm::vec3 between = pa.position - pb.position;
  // Convex or concave (a cell's dimple), so heights on either side may spread or squeeze.
  const float height = std::max(std::abs(pa.position.z) + a.radius(), std::abs(pb.position.z) + b.radius());
  const float lo = rule.closest_scale(height);
  const float hi = (1.f + rule.surface.lateral_stretch) * (1.f + rule.surface.curvature * height);
  const float reach = (a.radius() + b.radius()) / lo;
  if (glm::dot(between, between) >= reach * reach) return false;
  const glm::vec3 lateral(-between.x, -between.y, 0.f);  // b − a in the tile plane
  const glm::vec3 b_position = pb.position + (0.5f * (lo + hi) - 1.f) * lateral;
  const float stretch_widen = 0.5f * (hi - lo) * glm::length(lateral);
  // The tilt moves b along z by up to ±rise: three samples (−⅔, 0, +⅔ of it), each covering ±⅓.
  const float rise = std::min(rule.surface.tilt * glm::length(lateral), rule.surface.max_rise);
  if (rise == 0.f) return atoms_within(a, pa, b, pb, b_position, rule.clearance, stretch_widen);
  const float widen = stretch_widen + rise / 3.f;
  for (const float k : {0.f, -2.f / 3.f, 2.f / 3.f})
    if (atoms_within(a, pa, b, pb, b_position + glm::vec3(0.f, 0.f, k * rise), rule.clearance, widen)) return true;
  return false;
}

}  // namespace nano::tiles
