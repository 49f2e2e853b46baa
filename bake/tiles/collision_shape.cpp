#include "bake/tiles/collision_shape.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>

namespace nano::tiles {

namespace {

// Cells of edge `cell` from `lo` over `dims`, numbered x fastest.
struct CellGrid {
  glm::vec3 lo;
  float cell;
  glm::ivec3 dims;

  static CellGrid covering(glm::vec3 lo, glm::vec3 hi, float cell) {
    return {lo, cell, glm::max(glm::ivec3(glm::floor((hi - lo) / cell)) + 1, glm::ivec3(1))};
  }
  size_t count() const { return static_cast<size_t>(dims.x) * dims.y * dims.z; }
  uint32_t of(const glm::vec3& c) const {
    const glm::ivec3 g = glm::clamp(glm::ivec3(glm::floor((c - lo) / cell)), glm::ivec3(0), dims - 1);
    return static_cast<uint32_t>((g.z * dims.y + g.y) * dims.x + g.x);
  }
};

// Counting sort of `atoms` by cell (stable); returns the atoms, `start` gets count() + 1 offsets.
std::vector<AtomSphere> sort_by_cell(const std::vector<AtomSphere>& atoms, const CellGrid& grid,
                                     std::vector<uint32_t>& start) {
  start.assign(grid.count() + 1, 0);
  for (const AtomSphere& a : atoms) ++start[grid.of(a.centre) + 1];
  for (size_t i = 0; i < grid.count(); ++i) start[i + 1] += start[i];
  std::vector<AtomSphere> sorted(atoms.size());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (const AtomSphere& a : atoms) sorted[fill[grid.of(a.centre)]++] = a;
  return sorted;
}

// Cells of this many atom diameters per block: a handful of atoms each for lipids and proteins.
constexpr float kBlockCells = 2.f;

}  // namespace

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
  const CellGrid grid = CellGrid::covering(lo, hi, cell_);
  grid_min_ = lo;
  centre_max_ = hi;
  dims_ = grid.dims;
  atoms_ = sort_by_cell(type.atoms, grid, cell_start_);

  std::vector<uint32_t> block_start;
  block_atoms_ = sort_by_cell(type.atoms, CellGrid::covering(lo, hi, kBlockCells * cell_), block_start);
  for (size_t b = 0; b + 1 < block_start.size(); ++b) {
    if (block_start[b] == block_start[b + 1]) continue;
    Block block;
    block.begin = block_start[b];
    block.end = block_start[b + 1];
    glm::vec3 block_lo(INFINITY), block_hi(-INFINITY);
    for (uint32_t i = block.begin; i < block.end; ++i) {
      block_lo = glm::min(block_lo, block_atoms_[i].centre);
      block_hi = glm::max(block_hi, block_atoms_[i].centre);
      block.max_atom_radius = std::max(block.max_atom_radius, block_atoms_[i].radius);
    }
    block.centre = 0.5f * (block_lo + block_hi);
    for (uint32_t i = block.begin; i < block.end; ++i)
      block.spread = std::max(block.spread, glm::length(block_atoms_[i].centre - block.centre));
    blocks_.push_back(block);
  }
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
  // Cells lo.x..hi.x of one row are consecutive, and so are their atoms: one run per row (which
  // needs lo.x <= hi.x + 1 to stay inside the row, hence the return for a point beyond the grid).
  if (lo.x > hi.x) return false;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y) {
      const size_t row = (static_cast<size_t>(z) * dims_.y + y) * dims_.x;
      for (uint32_t i = cell_start_[row + lo.x]; i < cell_start_[row + hi.x + 1]; ++i) {
        const AtomSphere& a = atoms_[i];
        const float limit = clearance * (radius + a.radius);
        const glm::vec3 d = point - a.centre;
        if (glm::dot(d, d) < limit * limit) return true;
      }
    }
  return false;
}

namespace {

// Whether p lies `distance` or further from the box [lo, hi] (squared: no root per atom).
inline bool beyond_box(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi, float distance) {
  const glm::vec3 gap = glm::max(glm::max(lo - p, p - hi), glm::vec3(0.f));
  return glm::dot(gap, gap) >= distance * distance;
}

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
  const float widen_per_clearance = widen / clearance;
  // The rejects below skip only atoms whose per-atom tests cannot pass: they keep this much more
  // distance than those tests need, far above the float rounding of the positions (relative 1e-7)
  // and of a rotation product that is orthonormal only to float precision.
  const float slack = 1e-4f * (1.f + glm::length(shift) + walk.radius() + grid.radius());
  // The per-atom bounding-sphere test below, for the largest atom of a block.
  const auto sphere_limit = [&](float atom_radius) {
    return outer + atom_radius + widen + std::max(0.f, clearance - 1.f) * (atom_radius + grid.max_atom_radius());
  };
  // Furthest an atom centre can be from the grid's atom centres and still touch one of them.
  const auto touch_reach = [&](float atom_radius) {
    return clearance * (atom_radius + widen_per_clearance + grid.max_atom_radius());
  };
  for (const CollisionShape::Block& block : walk.blocks()) {
    const glm::vec3 centre = to_grid * block.centre + shift;
    const float far = block.spread + slack;
    const float block_limit = sphere_limit(block.max_atom_radius) + far;
    if (glm::dot(centre, centre) >= block_limit * block_limit) continue;
    if (beyond_box(centre, grid.centre_min(), grid.centre_max(), touch_reach(block.max_atom_radius) + far)) continue;
    for (uint32_t i = block.begin; i < block.end; ++i) {
      const AtomSphere& atom = walk.block_atoms()[i];
      const glm::vec3 q = to_grid * atom.centre + shift;
      // |atom centre in grid| + clearance * (r + r_grid) + widen, bounded with |centre| <= outer − r_grid.
      const float lim = sphere_limit(atom.radius);
      if (glm::dot(q, q) >= lim * lim) continue;
      if (beyond_box(q, grid.centre_min(), grid.centre_max(), touch_reach(atom.radius) + slack)) continue;
      if (grid.touches(q, atom.radius + widen_per_clearance, clearance)) return true;
    }
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
