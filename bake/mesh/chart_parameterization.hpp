#pragma once
// Flattening one disk-like chart with CGAL's Surface_mesh_parameterization. This header exposes no
// CGAL type: the CGAL code is confined to chart_parameterization_cgal.cpp.
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

enum class ChartMethod {
  lscm,        // least-squares conformal maps, free border (two pinned vertices): low stretch
  mean_value,  // mean-value coordinates inside a circular border fixed by arc length: injective
};
const char* to_string(ChartMethod method);

// UVs per vertex of the chart (`triangles` index `positions`, a triangulated topological disk with
// one border loop), or nothing when CGAL refuses it. Orientation and scale are whatever the method
// gives; uv_charts.cpp normalises and checks them.
std::optional<std::vector<glm::dvec2>> parameterize_chart(const std::vector<glm::dvec3>& positions,
                                                          const std::vector<Triangle>& triangles, ChartMethod method);

}  // namespace nano::mesh
