// Charts made by the baker (bake/mesh/uv_charts.hpp) on closed meshes of genus 0, 1 and 2 and on
// meshes with sharp features, none with UVs: check-mesh (the independent UV rules: inside the unit
// square, no zero-area or flipped triangle) must accept the result, no two UV triangles of the
// whole atlas may overlap (brute force here), and the stretch stays within the bound.
#include "bake/mesh/uv_charts.hpp"

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"

namespace nano::mesh {
namespace {

using glm::dvec2;
using glm::dvec3;

ProxyMesh without_uvs(ProxyMesh m) {
  m.uvs.clear();
  m.uv_triangles.clear();
  return m;
}

// A torus of radii R > r, nu × nv quads, outward (counter-clockwise seen from outside).
ProxyMesh torus(double R, double r, int nu, int nv) {
  ProxyMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.positions.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  const auto at = [&](int i, int j) { return std::uint32_t(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// The boundary of a set of unit voxels (edge `size` Å), as two triangles per exposed voxel face,
// outward. A plate with two holes is a closed surface of genus 2 with sharp edges everywhere.
ProxyMesh voxel_surface(const std::set<std::array<int, 3>>& voxels, double size) {
  ProxyMesh m;
  std::map<std::array<int, 3>, std::uint32_t> index;
  const auto vertex = [&](std::array<int, 3> p) {
    const auto [it, added] = index.try_emplace(p, std::uint32_t(m.positions.size()));
    if (added) m.positions.push_back(dvec3(p[0], p[1], p[2]) * size);
    return it->second;
  };
  for (const auto& v : voxels)
    for (int axis = 0; axis < 3; ++axis)
      for (int side : {-1, 1}) {
        std::array<int, 3> n = v;
        n[axis] += side;
        if (voxels.count(n)) continue;
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        std::array<int, 3> c = v;
        if (side > 0) c[axis] += 1;
        std::array<std::array<int, 3>, 4> q{c, c, c, c};
        q[1][a] += 1, q[2][a] += 1, q[2][b] += 1, q[3][b] += 1;
        std::uint32_t i[4];
        for (int k = 0; k < 4; ++k) i[k] = vertex(q[k]);
        // (a, b, axis) is right-handed: a→b counter-clockwise faces +axis.
        if (side > 0) m.triangles.push_back({i[0], i[1], i[2]}), m.triangles.push_back({i[0], i[2], i[3]});
        else m.triangles.push_back({i[0], i[2], i[1]}), m.triangles.push_back({i[0], i[3], i[2]});
      }
  return m;
}

// A plate of (3·holes + 1) × 3 × 1 voxels with the voxels (3h + 1, 1, 0) removed.
ProxyMesh plate_with_holes(int holes) {
  std::set<std::array<int, 3>> plate;
  for (int x = 0; x < 3 * holes + 1; ++x)
    for (int y = 0; y < 3; ++y) plate.insert({x, y, 0});
  for (int h = 0; h < holes; ++h) plate.erase({3 * h + 1, 1, 0});
  return voxel_surface(plate, 60.0);
}

int genus(const ProxyMesh& m) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  const long chi = long(m.positions.size()) - long(edges.size()) + long(m.triangles.size());
  return int((2 - chi) / 2);
}

double cross2(dvec2 a, dvec2 b, dvec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

// Brute force over every pair: a point strictly inside both triangles (each shrunk by 1e-6 of
// its size toward its centroid) exists iff no edge of either separates them.
std::size_t overlapping_pairs(const ProxyMesh& m) {
  std::vector<std::array<dvec2, 3>> tris;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    std::array<dvec2, 3> q{m.corner_uv(t, 0), m.corner_uv(t, 1), m.corner_uv(t, 2)};
    if (cross2(q[0], q[1], q[2]) < 0) std::swap(q[1], q[2]);
    const dvec2 c = (q[0] + q[1] + q[2]) / 3.0;
    for (dvec2& p : q) p = c + (p - c) * (1 - 1e-6);
    tris.push_back(q);
  }
  const auto separated = [](const std::array<dvec2, 3>& a, const std::array<dvec2, 3>& b) {
    for (int k = 0; k < 3; ++k) {
      bool outside = true;
      for (const dvec2& p : b) outside = outside && cross2(a[k], a[(k + 1) % 3], p) <= 0;
      if (outside) return true;
    }
    return false;
  };
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::size_t j = i + 1; j < tris.size(); ++j) pairs += !separated(tris[i], tris[j]) && !separated(tris[j], tris[i]);
  return pairs;
}

struct Case {
  const char* name;
  ProxyMesh mesh;
  int genus;
};

std::vector<Case> cases() {
  return {{"sphere", without_uvs(make_sphere_mesh(966, 500.0)), 0},
          {"red blood cell", without_uvs(make_rbc_mesh(2000)), 0},
          {"torus", torus(400.0, 150.0, 40, 16), 1},
          {"plate with two holes (sharp edges)", plate_with_holes(2), 2},
          {"plate with three holes", plate_with_holes(3), 3}};
}

TEST(UvCharts, MeshesOfGenusZeroToThreeGetValidUvs) {
  for (Case& c : cases()) {
    SCOPED_TRACE(c.name);
    ASSERT_EQ(genus(c.mesh), c.genus);
    ASSERT_FALSE(c.mesh.has_uvs());
    const ChartAtlas atlas = generate_uv_charts(c.mesh, "m.obj");
    ASSERT_TRUE(c.mesh.has_uvs());
    ASSERT_EQ(c.mesh.uv_triangles.size(), c.mesh.triangles.size());
    const MeshReport report = check_mesh(c.mesh, CheckOptions{});
    for (const MeshProblem& p : report.problems) ADD_FAILURE() << "face " << p.face << ": " << p.rule << " " << p.value;
    EXPECT_TRUE(report.usable());
    EXPECT_EQ(report.uv_charts, atlas.charts.size()) << "check-mesh counts the UV islands on its own";
    EXPECT_EQ(overlapping_pairs(c.mesh), 0u);
    // The bound holds per chart, and check-mesh's global σ (one UV scale for the whole atlas)
    // stays within it too: every chart keeps its area at the atlas scale.
    EXPECT_LE(atlas.max_stretch, 2.0);
    EXPECT_LE(std::max(report.sigma_max, 1.0 / report.sigma_min), 2.0 * (1 + 1e-6));
    EXPECT_GE(atlas.mean_stretch, 1.0);
    EXPECT_GT(atlas.seam_length, 0.0);
    EXPECT_GT(atlas.packing_efficiency, 0.2);
    EXPECT_LE(atlas.packing_efficiency, 1.0);
    std::printf("%-36s genus %d, %5zu triangles: %3zu charts, seam %.0f Å, stretch max %.3f mean %.3f, packing %.2f, %.3f s\n",
                c.name, c.genus, c.mesh.triangles.size(), atlas.charts.size(), atlas.seam_length, atlas.max_stretch,
                atlas.mean_stretch, atlas.packing_efficiency, atlas.seconds);
  }
}

TEST(UvCharts, AFlatRegionWithHolesIsCutIntoDisks) {
  ProxyMesh plate = plate_with_holes(2);
  const ChartAtlas atlas = generate_uv_charts(plate, "m.obj");
  // Faces of one flat side keep their shape exactly: planar charts flatten isometrically.
  EXPECT_NEAR(atlas.max_stretch, 1.0, 1e-6);
  // The top face (a 7 × 3 plate with two holes) cannot be one chart: six sides become at least
  // eight charts.
  EXPECT_GE(atlas.charts.size(), 8u);
}

TEST(UvCharts, SameSeedSameUvs) {
  ProxyMesh a = torus(400.0, 150.0, 30, 12), b = a;
  generate_uv_charts(a, "m.obj", {.seed = 7});
  generate_uv_charts(b, "m.obj", {.seed = 7});
  EXPECT_EQ(a.uvs, b.uvs);
  EXPECT_EQ(a.uv_triangles, b.uv_triangles);
}

TEST(UvCharts, TighterNormalConeMeansMoreChartsAndLessStretch) {
  ProxyMesh wide = without_uvs(make_sphere_mesh(966, 500.0)), tight = wide;
  const ChartAtlas w = generate_uv_charts(wide, "m.obj", {.max_normal_angle_degrees = 70});
  const ChartAtlas t = generate_uv_charts(tight, "m.obj", {.max_normal_angle_degrees = 25});
  EXPECT_GT(t.charts.size(), w.charts.size());
  EXPECT_GT(t.seam_length, w.seam_length);
  EXPECT_LE(t.max_stretch, w.max_stretch + 1e-9);
}

TEST(UvCharts, RefusesNonManifoldAndDegenerateMeshes) {
  ProxyMesh fin = torus(400.0, 150.0, 12, 6);
  fin.positions.push_back({0, 0, 999});
  fin.triangles.push_back({fin.triangles[0][0], fin.triangles[0][1], std::uint32_t(fin.positions.size() - 1)});
  // The mesh's own faults are input: refused from the source the caller names, the edge or triangle named.
  try {
    generate_uv_charts(fin, {"fin.obj", "compartment 'c'"});
    ADD_FAILURE() << "charted a non-manifold edge";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "fin.obj");
    EXPECT_EQ(e.where(), "compartment 'c'");
    EXPECT_NE(e.rule().find("cannot make UV charts: edge "), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find("is non-manifold or inconsistently oriented"), std::string::npos) << e.what();
  }
  ProxyMesh flat = torus(400.0, 150.0, 12, 6);
  flat.triangles[3] = {flat.triangles[3][0], flat.triangles[3][0], flat.triangles[3][1]};
  try {
    generate_uv_charts(flat, "flat.obj");
    ADD_FAILURE() << "charted a zero-area triangle";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "flat.obj: cannot make UV charts: triangle 3 has zero area");
  }
  ProxyMesh none;
  EXPECT_THROW(generate_uv_charts(none, "none.obj"), InputError);
  // Bad options are the caller's bug (the baker's own constants), not input.
  ProxyMesh sphere = without_uvs(make_sphere_mesh(200, 100.0));
  EXPECT_THROW(generate_uv_charts(sphere, "s.obj", {.max_normal_angle_degrees = 95}), std::invalid_argument);
  EXPECT_THROW(generate_uv_charts(sphere, "s.obj", {.max_stretch = 0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace nano::mesh
