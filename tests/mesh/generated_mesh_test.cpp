// Generated proxy meshes against analytic geometry: the Evans–Fung numbers of BIOLOGY.md §1.2
// and the sphere's 4πR² and 4/3·πR³.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
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

TEST(RbcMesh, PassesCheckMeshWithTwoDisksSeamAlongTheRim) {
  const ProxyMesh mesh = make_rbc_mesh(3000);
  expect_usable_after_round_trip(mesh, "rbc.obj", 1.4);  // measured σ ∈ [0.846, 1.058]
  testing::TempDir dir;
  write_obj(dir.path() / "r.obj", mesh);
  const MeshReport r = check_mesh(read_proxy_mesh(dir.path() / "r.obj"), CheckOptions{});
  EXPECT_EQ(r.uv_charts, 2u);
  EXPECT_NEAR(r.seam_length, 2 * pi * 3.91e4, 0.01 * 2 * pi * 3.91e4);  // the rim circle
}

}  // namespace
}  // namespace nano::mesh
