#pragma once
// UVs made by the baker for a mesh that has none (or whose UVs fail the checks): the surface is cut
// into disk-like charts, each chart flattened by CGAL (LSCM, or mean-value coordinates inside a
// fixed circular border when LSCM folds or stretches too much), and the charts packed into the unit
// UV square with gutters, at one scale for all (UV area proportional to surface area, so the
// membrane's tiles keep one density across charts).
//
// Charts grow from seed faces over edges while a face's normal stays within max_normal_angle of
// the seed's (seams fall along high-curvature and feature edges), then neighbouring charts merge
// while their union keeps every normal within that angle of its mean; a chart that is not a disk (a
// hole, a handle, a pinched vertex) or whose flattening fails the stretch bound is cut in two
// across its longest axis, down to single triangles if need be. Deterministic for a seed.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/mesh/proxy_mesh.hpp"
#include "common/error.hpp"

namespace nano::mesh {

struct ChartOptions {
  double max_normal_angle_degrees = 60.0;
  // Per triangle max(σ1, 1/σ2) of the chart's map scaled to keep its area: 1 is isometric.
  double max_stretch = 2.0;
  double gutter = 0.0;  // Å between packed charts; 0 picks half the mean edge length
  std::uint64_t seed = 1;
};

struct ChartSummary {
  std::size_t triangles = 0;
  double area = 0.0;         // Å²
  double max_stretch = 1.0;  // as ChartOptions::max_stretch
  std::string method;        // chart_parameterization.hpp to_string
};

struct ChartAtlas {
  std::vector<ChartSummary> charts;
  double seam_length = 0.0;       // Å: surface edges whose two faces lie in different charts
  double max_stretch = 1.0;       // over every triangle
  double mean_stretch = 1.0;      // area-weighted
  double packing_efficiency = 0;  // chart area / UV square area, both in Å² at the atlas scale
  double uv_scale = 0.0;          // Å of surface per UV unit (the same for every chart)
  double seconds = 0.0;
};

// Replaces mesh.uvs / mesh.uv_triangles with generated ones. The mesh must be an edge-manifold
// triangle mesh (every edge on at most two faces, consistently oriented) without zero-area
// triangles: throws an InputError from `source` (the mesh file, and the compartment the scene
// reads it for) naming the first offending edge or triangle otherwise.
ChartAtlas generate_uv_charts(ProxyMesh& mesh, const InputSource& source, const ChartOptions& options = {});

nlohmann::json to_json(const ChartAtlas& atlas);

}  // namespace nano::mesh
