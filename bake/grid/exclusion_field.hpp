#pragma once
// A compartment's exclusion field (shaders/shared/medium.h): how far each point of compartment
// space stands clear of what the compartment draws, sampled on a grid for the medium's keep rule.
// What triangle t draws lies within reach[t] of it, so outside the mesh a point p stands clear by
// min over t of (|p − t| − reach[t]): a virion's spikes keep the medium away from their own
// triangles only, not from the whole surface. Inside, the same less twice the distance to the mesh:
// continuous across the surface (interpolation there neither overstates nor starves the room
// outside) and at most −(distance + least reach), so no copy is ever kept there.
// Node values are exact (CGAL's distance, inside test and box query through MeshSurface, then
// exact point-triangle distances); between nodes the rule interpolates, and the baker measures,
// where the rule can decide, how much interpolation overstates the true value, and keeps that
// (doubled) as the field's margin.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/grid/mesh_surface.hpp"

namespace nano::grid {

struct ExclusionFieldRequest {
  // Per triangle of the surface's mesh: how far what it draws reaches from it (Å, ≥ 0). Empty:
  // nothing beyond the mesh (a compartment without a membrane).
  std::vector<float> reach;
  double medium_reach = 0.0;  // the largest medium copy's bounding radius plus the clearance (Å)
  std::size_t max_nodes = 1u << 20;  // the grid's node budget
  double min_spacing = 8.0;          // Å: finer grids only cost memory
  int threads = 1;
};

struct ExclusionField {
  glm::dvec3 origin{0.0};  // node (0, 0, 0)
  double spacing = 0.0;
  glm::ivec3 dims{0};      // nodes per axis
  std::vector<float> values;  // node i + X·(j + Y·k): exact_clearance, clamped to ±clamp
  double clamp = 0.0;
  double least_reach = 0.0, largest_reach = 0.0;  // the request's reach over the triangles
  double measured_excess = 0.0;  // the most the interpolated value exceeded the true one at the samples
  double margin = 0.0;           // what the rule subtracts: 2 × measured_excess + 0.5 Å
  std::size_t samples = 0;       // points where the excess was measured

  std::size_t node_index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(dims.x) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims.y) * k);
  }
};

// How far points stand clear of what a surface's triangles draw (see the top), exact in double.
class DrawnClearance {
public:
  // Throws InputError when `reach` is neither empty nor one finite value ≥ 0 per triangle.
  DrawnClearance(const MeshSurface& surface, std::vector<float> reach);
  // The value at p, or `enough` where it is at least that (the field clamps there).
  double at(const glm::dvec3& p, double enough = std::numeric_limits<double>::infinity()) const;
  // The same once the caller knows p's distance to the mesh and its side; at or below −enough
  // inside may be returned as −enough.
  double outside(const glm::dvec3& p, double distance, double enough) const;
  double inside(const glm::dvec3& p, double distance, double enough) const;
  double least_reach() const { return least_; }
  double largest_reach() const { return largest_; }

private:
  // The few triangles reaching farther than most (a virion's spikes): tested one by one, so the box
  // searched for the others grows with their own spread of reach only.
  struct Tall {
    std::uint32_t triangle;
    glm::dvec3 centre;  // of the triangle's bounding sphere
    double radius;
  };
  const MeshSurface& surface_;
  std::vector<float> reach_;
  double least_ = 0.0, largest_ = 0.0;
  double common_largest_ = 0.0;  // the largest reach among the triangles not in tall_
  std::vector<Tall> tall_;
};

// Bakes the field over the mesh's bounding box grown by the largest reach + medium_reach + two spacings,
// with the coarsest spacing (≥ min_spacing) whose grid fits max_nodes.
ExclusionField bake_exclusion_field(const MeshSurface& surface, const ExclusionFieldRequest& request);

// The field's interpolated value at p, as medium.h computes it (in double), or +clamp beyond the grid.
double interpolated_clearance(const ExclusionField& field, const glm::dvec3& p);

}  // namespace nano::grid
