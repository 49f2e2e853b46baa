// Generated proxy meshes against analytic geometry: the Evans–Fung numbers of BIOLOGY.md §1.2
// and the sphere's 4πR² and 4/3·πR³.
#include <cmath>
#include <map>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "bake/mesh/box_mesh.hpp"
#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/uv_distortion.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double um = angstrom_per_micrometre;

// Oracle measurements straight from the triangles (not through check-mesh).
double surface_area(const ProxyMesh& m) {
  double a = 0;
  for (const Triangle& t : m.triangles)
    a += 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
  return a;
}
double enclosed_volume(const ProxyMesh& m) {
  double v = 0;
  for (const Triangle& t : m.triangles)
    v += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
  return v;
}

// Total length of the edges whose two triangles do not share both endpoint UV indices.
double rbc_seam_length(const ProxyMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, std::uint32_t>>> uv_at;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      const std::uint32_t ua = m.uv_triangles[t][k], ub = m.uv_triangles[t][(k + 1) % 3];
      uv_at[{std::min(a, b), std::max(a, b)}].push_back(a < b ? std::pair(ua, ub) : std::pair(ub, ua));
    }
  double length = 0;
  for (const auto& [edge, uvs] : uv_at)
    if (uvs.size() == 2 && uvs[0] != uvs[1]) length += glm::distance(m.positions[edge.first], m.positions[edge.second]);
  return length;
}

// Area-weighted mean of σ1·σ2 / σmin² (σmin: the smallest stretch over the mesh, the tile scale):
// how much sparser than in its tiles the membrane ends up on the surface.
double mean_area_stretch(const ProxyMesh& m) {
  const double tile_scale = smallest_stretch(m);
  double weighted = 0, area = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const SingularValues s = singular_values(*uv_jacobian(m, t));
    weighted += world_area(m, t) * s.major * s.minor / (tile_scale * tile_scale);
    area += world_area(m, t);
  }
  return weighted / area;
}

// Measured values of Evans & Fung 1972 as listed in shared/data/BIOLOGY.md §1.1.
constexpr double rbc_diameter_um = 7.82, rbc_rim_um = 2.58, rbc_dimple_um = 0.81;
constexpr double rbc_area_um2 = 135.0, rbc_volume_um3 = 94.0;

TEST(RbcMesh, DefaultResolutionHasEvansFungDimensions) {
  const ProxyMesh mesh = make_rbc_mesh(3000);
  double max_r = 0, max_z = 0, min_z = 0, axis_top = 0, axis_bottom = 0;
  for (const glm::dvec3& p : mesh.positions) {
    const double r = std::hypot(p.x, p.y);
    max_r = std::max(max_r, r);
    max_z = std::max(max_z, p.z);
    min_z = std::min(min_z, p.z);
    if (r == 0.0) (p.z > 0 ? axis_top : axis_bottom) = p.z;
  }
  EXPECT_NEAR(2 * max_r / um, rbc_diameter_um, 0.02 * rbc_diameter_um);
  EXPECT_NEAR((max_z - min_z) / um, rbc_rim_um, 0.02 * rbc_rim_um);
  EXPECT_NEAR((axis_top - axis_bottom) / um, rbc_dimple_um, 0.02 * rbc_dimple_um);
  EXPECT_NEAR(surface_area(mesh) / (um * um), rbc_area_um2, 0.02 * rbc_area_um2);
  EXPECT_NEAR(enclosed_volume(mesh) / (um * um * um), rbc_volume_um3, 0.02 * rbc_volume_um3);
}

TEST(RbcMesh, ShapeFunctionMatchesTheFormula) {
  const EvansFungShape shape;
  EXPECT_NEAR(2 * shape.half_thickness(0) / um, 0.81, 0.005);           // c0 = R0·C0 = 0.810 µm
  EXPECT_DOUBLE_EQ(shape.half_thickness(shape.r0), 0.0);
  const double rho = 0.7, r = rho * shape.r0;                            // a point by hand
  EXPECT_NEAR(shape.half_thickness(r), 0.5 * 3.91e4 * std::sqrt(1 - 0.49) * (0.2072 + 2.0026 * 0.49 - 1.1228 * 0.2401), 1e-9);
}

TEST(RbcMesh, TriangleCountWithinQuarterOfTarget) {
  for (int target : {200, 1000, 3000, 12000}) {
    const double n = static_cast<double>(make_rbc_mesh(target).triangles.size());
    EXPECT_NEAR(n / target, 1.0, 0.25) << target;
  }
  EXPECT_THROW(make_rbc_mesh(100), InputError);
}

TEST(SphereMesh, TriangleCountWithinQuarterOfTarget) {
  for (int target : {48, 100, 1000, 1500, 10000}) {
    const double n = static_cast<double>(make_sphere_mesh(target, 1.0).triangles.size());
    EXPECT_NEAR(n / target, 1.0, 0.25) << target;
  }
  EXPECT_THROW(make_sphere_mesh(47, 1.0), InputError);
  EXPECT_THROW(make_sphere_mesh(1000, -1.0), InputError);
}

TEST(SphereMesh, VerticesOnSphereAndAreaVolumeConverge) {
  const double radius = 500.0;
  double previous_area_error = 1, previous_volume_error = 1;
  for (int target : {300, 1200, 4800}) {
    const ProxyMesh mesh = make_sphere_mesh(target, radius);
    for (const glm::dvec3& p : mesh.positions) ASSERT_NEAR(glm::length(p), radius, 1e-9);
    // Inscribed polyhedron: both fall short by O(h²), h ~ R·sqrt(8π / N).
    const double area_error = 1 - surface_area(mesh) / (4 * pi * radius * radius);
    const double volume_error = 1 - enclosed_volume(mesh) / (4.0 / 3.0 * pi * std::pow(radius, 3));
    const double h2 = 8 * pi / static_cast<double>(mesh.triangles.size());
    EXPECT_GT(area_error, 0);
    EXPECT_LT(area_error, 0.5 * h2) << target;
    EXPECT_LT(volume_error, h2) << target;
    EXPECT_LT(area_error, previous_area_error / 3) << target;  // 4× the triangles: ~4× smaller error
    EXPECT_LT(volume_error, previous_volume_error / 3) << target;
    previous_area_error = area_error;
    previous_volume_error = volume_error;
  }
}

// (b): what the baker writes, read back as any user's file would be, passes check-mesh.
void expect_usable_after_round_trip(const ProxyMesh& mesh, const char* name, double max_sigma_ratio) {
  testing::TempDir dir;
  const auto file = dir.path() / name;
  write_obj(file, mesh);
  const MeshReport r = check_mesh(read_proxy_mesh(file), CheckOptions{});
  EXPECT_TRUE(r.usable()) << report_to_text(r, name);
  EXPECT_TRUE(r.closed && r.manifold && r.oriented && r.outward);
  EXPECT_TRUE(r.warnings.empty()) << report_to_text(r, name);
  EXPECT_EQ(r.mirrored_triangles, 0u);
  EXPECT_LT(r.sigma_max / r.sigma_min, max_sigma_ratio);
}

// The box a cytoplasm-only recipe fills: closed, outward, its volume and area the box's, six charts
// of one stretch each (σ ratio: the cells are square, the faces not).
TEST(BoxMesh, IsTheBoxClosedOutwardWithSixCharts) {
  const ProxyMesh mesh = make_box_mesh({700.0, 1200.0, 2200.0});
  ASSERT_EQ(mesh.triangles.size(), 12u);
  expect_usable_after_round_trip(mesh, "box.obj", 2200.0 / 700.0 + 1e-6);
  testing::TempDir dir;
  write_obj(dir.path() / "b.obj", mesh);
  const MeshReport r = check_mesh(read_proxy_mesh(dir.path() / "b.obj"), CheckOptions{});
  EXPECT_EQ(r.uv_charts, 6u);
  ASSERT_TRUE(r.volume.has_value());
  EXPECT_NEAR(*r.volume, 700.0 * 1200.0 * 2200.0, 1e-3);
  EXPECT_NEAR(r.area, 2.0 * (700.0 * 1200.0 + 1200.0 * 2200.0 + 2200.0 * 700.0), 1e-3);
  for (const glm::dvec3& p : mesh.positions) EXPECT_EQ(glm::abs(p), glm::dvec3(350.0, 600.0, 1100.0));
  EXPECT_THROW(make_box_mesh({700.0, 0.0, 1.0}), InputError);
  EXPECT_THROW(make_box_mesh({700.0, NAN, 1.0}), InputError);
}

TEST(SphereMesh, PassesCheckMeshWithSixChartsAndLowDistortion) {
  const ProxyMesh mesh = make_sphere_mesh(1452, 500.0);
  expect_usable_after_round_trip(mesh, "sphere.obj", 1.6);  // measured σ ∈ [0.759, 1.201]
  testing::TempDir dir;
  write_obj(dir.path() / "s.obj", mesh);
  const MeshReport r = check_mesh(read_proxy_mesh(dir.path() / "s.obj"), CheckOptions{});
  EXPECT_EQ(r.uv_charts, 6u);
  // Seams: the 12 cube edges, each n = 11 grid edges; total length 12 quarter-circle-ish arcs
  // of angle acos(1/3) (the angle between adjacent cube corners seen from the centre), as chords.
  EXPECT_EQ(r.seam_edges, 12u * 11u);
  EXPECT_NEAR(r.seam_length, 12 * 500.0 * std::acos(1.0 / 3.0), 0.01 * 12 * 500.0 * std::acos(1.0 / 3.0));
}

// The interpolated normals of a sphere turn at 1/R; a flat patch's not at all; the RBC's fastest
// turn is at its rim (radius of curvature ~1 µm at R0 = 3.91 µm, far below the ~µm⁻¹ of its faces).
TEST(NormalTurnRate, SphereIsOneOverRadiusFlatIsZero) {
  for (const double radius : {100.0, 500.0}) {
    const double rate = normal_turn_rate(make_sphere_mesh(1452, radius));
    EXPECT_GT(rate, 0.95 / radius) << radius;
    EXPECT_LT(rate, 1.3 / radius) << radius;
  }
  ProxyMesh flat;
  flat.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {10, 10, 0}};
  flat.triangles = {{0, 1, 2}, {1, 3, 2}};
  flat.normals = {{0, 0, 1}};
  flat.normal_triangles = {{0, 0, 0}, {0, 0, 0}};
  EXPECT_EQ(normal_turn_rate(flat), 0.0);
  EXPECT_EQ(largest_normal_tilt(flat), 0.0);
  EXPECT_EQ(largest_facet_sag(flat), 0.0);
  const double rbc = normal_turn_rate(make_rbc_mesh(3000));
  EXPECT_GT(rbc, 1.0 / 39100.0);
  EXPECT_LT(rbc, 1.0 / 3000.0);
}

// A leaflet d Å out from a sphere of radius R spreads over ((R + d) / R)² of its area, one d Å in
// over ((R − d) / R)² (the generated sphere's corner normals are radial, so its facets scale
// exactly); without normals the offset is the mesh itself.
TEST(OffsetSurfaceArea, SphereLeafletsScaleAsTheirRadiiSquared) {
  const double radius = 450.0;
  const ProxyMesh sphere = make_sphere_mesh(6000, radius);
  const double mid = offset_surface_area(sphere, 0.0);
  for (const double d : {12.3, -12.3, 40.0})
    EXPECT_NEAR(offset_surface_area(sphere, d) / mid, std::pow((radius + d) / radius, 2.0), 1e-7) << d;
  ProxyMesh bare = sphere;
  bare.normals.clear();
  bare.normal_triangles.clear();
  EXPECT_DOUBLE_EQ(offset_surface_area(bare, 12.3), mid);
  EXPECT_NEAR(mid, 4.0 * M_PI * radius * radius, 0.01 * mid);
}

// On a sphere (corner normals radial) a corner normal leans from its face by about ρ/R (ρ: corner to
// centroid) and the facet sags about ρ²/(2R) below the sphere; both shrink as the mesh is refined.
TEST(NormalTilt, SphereFacetsTiltAndSagAsTheirSizeSays) {
  constexpr double radius = 450.0;
  double previous_tilt = 1.0, previous_sag = 1e9;
  for (const int target : {1452, 6000}) {
    const ProxyMesh mesh = make_sphere_mesh(target, radius);
    double rho = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::dvec3 c = (mesh.corner_position(t, 0) + mesh.corner_position(t, 1) + mesh.corner_position(t, 2)) / 3.0;
      for (int k = 0; k < 3; ++k) rho = std::max(rho, glm::length(mesh.corner_position(t, k) - c));
    }
    const double tilt = largest_normal_tilt(mesh), sag = largest_facet_sag(mesh);
    EXPECT_GT(tilt, 0.8 * rho / radius) << target;
    EXPECT_LT(tilt, 1.2 * rho / radius) << target;
    EXPECT_GT(sag, 0.9 * rho * rho / (2 * radius)) << target;
    EXPECT_LT(sag, 1.3 * rho * rho / (2 * radius)) << target;
    EXPECT_LT(tilt, previous_tilt);
    EXPECT_LT(sag, previous_sag);
    previous_tilt = tilt, previous_sag = sag;
  }
}

// Copies on the smooth surface (Phong, shape factor 1/2) stand along interpolated normals that
// follow that surface: on a sphere they are off by a small fraction of the flat facets' tilt, and
// shape factor 0 is the flat facet (its sampled tilt is the corner-normal one).
TEST(NormalTilt, SmoothSurfaceFollowsTheInterpolatedNormals) {
  const ProxyMesh sphere = make_sphere_mesh(1452, 450.0);
  const double flat = largest_normal_tilt(sphere);
  EXPECT_NEAR(largest_smooth_normal_tilt(sphere, 0.0), flat, 0.02 * flat);
  EXPECT_LT(largest_smooth_normal_tilt(sphere, 0.5), 0.1 * flat);
  EXPECT_GT(largest_smooth_normal_tilt(sphere, 1.0), largest_smooth_normal_tilt(sphere, 0.5)) << "Phong's full lift overshoots";
  const ProxyMesh rbc = make_rbc_mesh(3000);
  EXPECT_LT(largest_smooth_normal_tilt(rbc, 0.5), 0.25 * largest_normal_tilt(rbc));
  ProxyMesh plane;
  plane.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  plane.triangles = {{0, 1, 2}};
  plane.normals = {{0, 0, 1}};
  plane.normal_triangles = {{0, 0, 0}};
  EXPECT_EQ(largest_smooth_normal_tilt(plane, 0.5), 0.0);
}

TEST(RbcMesh, PassesCheckMeshWithBandChartsAndLowDistortion) {
  const ProxyMesh mesh = make_rbc_mesh(3000);
  expect_usable_after_round_trip(mesh, "rbc.obj", 1.04);  // measured σ ∈ [0.992, 1.020]
  testing::TempDir dir;
  write_obj(dir.path() / "r.obj", mesh);
  const MeshReport r = check_mesh(read_proxy_mesh(dir.path() / "r.obj"), CheckOptions{});
  // Two polar caps, a cylinder around the rim and the cone bands between them (two per half).
  EXPECT_EQ(r.uv_charts, 7u);
  EXPECT_NEAR(r.seam_length, rbc_seam_length(mesh), 1e-6 * r.seam_length);
}

// The UV→surface map of every chart stretches by nearly the same amount in every direction, so
// with the tile scale at the smallest stretch little of the membrane is spread thin.
TEST(RbcMesh, ChartsAreNearlyIsotropic) {
  for (const int target : {1000, 3000, 10000}) {
    const ProxyMesh mesh = make_rbc_mesh(target);
    EXPECT_LE(chart_anisotropy(mesh), 1.04) << target;
    EXPECT_LE(mean_area_stretch(mesh), 1.03) << target;
  }
}

// Overlapping UV triangles, of one chart or two: pairs whose boxes meet and that no edge line of
// either separates (exactly for a shared corner, whose orientation is 0).
std::size_t overlapping_uv_triangles(const ProxyMesh& mesh) {
  const auto box = [&](std::size_t t) {
    const glm::dvec2 a = mesh.corner_uv(t, 0), b = mesh.corner_uv(t, 1), c = mesh.corner_uv(t, 2);
    return std::pair(glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)));
  };
  const auto outside_an_edge = [&](std::size_t t, std::size_t other) {
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 a = mesh.corner_uv(t, k), e = mesh.corner_uv(t, (k + 1) % 3) - a;
      bool all_outside = true;
      for (int c = 0; c < 3; ++c) {
        const glm::dvec2 p = mesh.corner_uv(other, c) - a;
        all_outside = all_outside && e.x * p.y - e.y * p.x <= 0.0;
      }
      if (all_outside) return true;
    }
    return false;
  };
  std::size_t overlapping = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto [lo, hi] = box(t);
    for (std::size_t u = t + 1; u < mesh.triangles.size(); ++u) {
      const auto [lo2, hi2] = box(u);
      if (hi.x < lo2.x || hi2.x < lo.x || hi.y < lo2.y || hi2.y < lo.y) continue;
      overlapping += !outside_an_edge(t, u) && !outside_an_edge(u, t);
    }
  }
  return overlapping;
}

// 1,000 triangles keep the rim as a seam, 2,000 split a cone into two sectors.
TEST(RbcMesh, UvTrianglesAreCounterClockwiseInsideTheSquareAndDoNotOverlap) {
  for (const int target : {1000, 2000, 3000, 10000}) {
    const ProxyMesh mesh = make_rbc_mesh(target);
    for (const glm::dvec2& uv : mesh.uvs) {
      EXPECT_GT(std::min(uv.x, uv.y), 0.0) << target;
      EXPECT_LT(std::max(uv.x, uv.y), 1.0) << target;
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) ASSERT_GT(uv_signed_area(mesh, t), 0.0) << target << " " << t;
    EXPECT_EQ(overlapping_uv_triangles(mesh), 0u) << target;
  }
}

// Seams cut the membrane's tiling: the band charts trade the rim circle for the circles between
// bands and one meridional cut per cone band.
TEST(RbcMesh, SeamsStayShort) {
  const double rim = 2 * pi * EvansFungShape{}.r0;
  EXPECT_LE(rbc_seam_length(make_rbc_mesh(3000)), 6 * rim);  // measured 4.46× the rim circumference
}

}  // namespace
}  // namespace nano::mesh
