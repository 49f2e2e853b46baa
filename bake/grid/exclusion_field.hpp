#pragma once
// A compartment's exclusion field (shaders/shared/medium.h): how far each point of compartment
// space stands clear of what the compartment draws, sampled on a grid for the medium's keep rule.
// Node values are exact (CGAL's distance and inside test, through MeshSurface); between nodes the
// rule interpolates, and the baker measures, where the rule can decide, how much interpolation
// overstates the true value, and keeps that (doubled) as the field's margin.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/grid/mesh_surface.hpp"

namespace nano::grid {

struct ExclusionFieldRequest {
  double shell_reach = 0.0;   // how far the membrane shell reaches beyond the mesh (Å, ≥ 0)
  double medium_reach = 0.0;  // the largest medium copy's bounding radius plus the clearance (Å)
  std::size_t max_nodes = 1u << 20;  // the grid's node budget
  double min_spacing = 8.0;          // Å: finer grids only cost memory
  int threads = 1;
};

struct ExclusionField {
  glm::dvec3 origin{0.0};  // node (0, 0, 0)
  double spacing = 0.0;
  glm::ivec3 dims{0};      // nodes per axis
  std::vector<float> values;  // node i + X·(j + Y·k): signed distance to the mesh − shell_reach, clamped to ±clamp
  double clamp = 0.0;
  double shell_reach = 0.0;      // the request's: what the values are less than the distance
  double measured_excess = 0.0;  // the most the interpolated value exceeded the true one at the samples
  double margin = 0.0;           // what the rule subtracts: 2 × measured_excess + 0.5 Å
  std::size_t samples = 0;       // points where the excess was measured

  std::size_t node_index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(dims.x) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims.y) * k);
  }
};

// The signed distance from p to the surface (negative strictly inside), less the shell's reach.
double exact_clearance(const MeshSurface& surface, const glm::dvec3& p, double shell_reach);

// Bakes the field over the mesh's bounding box grown by shell_reach + medium_reach + two spacings,
// with the coarsest spacing (≥ min_spacing) whose grid fits max_nodes.
ExclusionField bake_exclusion_field(const MeshSurface& surface, const ExclusionFieldRequest& request);

// The field's interpolated value at p, as medium.h computes it (in double), or +clamp beyond the grid.
double interpolated_clearance(const ExclusionField& field, const glm::dvec3& p);

}  // namespace nano::grid
