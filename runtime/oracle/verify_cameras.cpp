#include "runtime/oracle/verify_cameras.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "format/package_view.hpp"
#include "shared/ownership.h"
#include "shared/tile_mapper.h"

namespace nano::oracle {
namespace {

using format::SectionKind;
using glm::dvec3;

struct InstanceFrame {
  glm::dmat3 linear{1.0};
  dvec3 translation{0.0};
  dvec3 point(const dvec3& p) const { return linear * p + translation; }
  dvec3 normal(const dvec3& n) const { return glm::normalize(glm::transpose(glm::inverse(linear)) * n); }
};

InstanceFrame frame_of(const gpu::CompartmentInstance& ci) {
  const format::InstanceTransform t = format::instance_transform(ci);
  return {t.linear, t.translation};
}

// Any unit vector perpendicular to n.
dvec3 perpendicular(const dvec3& n) {
  const dvec3 a = std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, a));
}

// The nearest point to `eye`, stepping along a spiral in the plane (u, v), that lies outside every
// atom by more than a hundredth of an ångström: the inside-prism view looks from between the lipids.
// An eye inside an atom is the inside-atom view's case, and one in an atom's radius tolerance would
// make every tie there a question verify's radius judge cannot answer.
dvec3 clear_of_atoms(const ExplicitScene& scene, const dvec3& eye, const dvec3& u, const dvec3& v) {
  constexpr double kReach = 4.0;  // Å: beyond the largest atom radius
  for (int k = 0; k < 400; ++k) {
    const double angle = 0.7 * k, radius = 0.05 * k;
    const dvec3 candidate = eye + radius * (std::cos(angle) * u + std::sin(angle) * v);
    bool inside = false;
    scene.for_each_atom(WorldBox{candidate - kReach, candidate + kReach}, [&](const AtomSample& a) {
      inside = inside || glm::length(a.position - candidate) < a.radius + 0.01;
    });
    if (!inside) return candidate;
  }
  return eye;
}

// A triangle that owns molecules (a shell above it), from the middle of the mesh's triangle list on
// (deterministic, away from the first chart's corner); NANO_NO_INDEX when none does.
std::uint32_t owning_triangle_mid_mesh(const gpu::Mesh& mesh, std::span<const gpu::TriangleShell> shells) {
  for (std::uint32_t k = 0; k < mesh.triangle_count; ++k) {
    const std::uint32_t cand = mesh.first_triangle + (mesh.triangle_count / 2 + k) % mesh.triangle_count;
    if (shells[cand].h_plus > 0) return cand;
  }
  return gpu::NANO_NO_INDEX;
}

// The membrane cameras around triangle t of instance i's mesh.
void add_membrane_cameras(const format::Package& p, const ExplicitScene& scene, std::uint32_t i, std::uint32_t t,
                          std::vector<VerifyCamera>& cams) {
  const gpu::CompartmentInstance& inst = p.records<SectionKind::compartment_instances>()[i];
  const gpu::Compartment& c = p.records<SectionKind::compartments>()[inst.compartment];
  const gpu::Mesh& mesh = p.records<SectionKind::meshes>()[c.mesh];
  const auto positions = p.records<SectionKind::vertex_positions>();
  const auto normals = p.records<SectionKind::vertex_normals>();
  const auto uvs = p.records<SectionKind::vertex_uvs>();
  const InstanceFrame f = frame_of(inst);
  const gpu::Triangle& tri = p.records<SectionKind::triangles>()[t];
  const std::uint32_t v[3] = {mesh.first_vertex + tri.v0, mesh.first_vertex + tri.v1, mesh.first_vertex + tri.v2};
  const dvec3 P[3] = {dvec3(positions[v[0]]), dvec3(positions[v[1]]), dvec3(positions[v[2]])};
  const dvec3 centroid_local = (P[0] + P[1] + P[2]) / 3.0;
  const dvec3 n_local = glm::normalize(glm::cross(P[1] - P[0], P[2] - P[0]));
  // Outward: away from the mesh's box centre, so every view looks into the compartment and rays
  // that pass the membrane meet its dense interior instead of escaping to far instances (which
  // would make the oracle instantiate whole cells).
  const dvec3 mesh_centre = 0.5 * (dvec3(mesh.aabb_min) + dvec3(mesh.aabb_max));
  const dvec3 n_out = glm::dot(n_local, centroid_local - mesh_centre) < 0 ? -n_local : n_local;
  const dvec3 C = f.point(centroid_local), N = f.normal(n_out);
  const dvec3 T = glm::normalize(f.point(P[1]) - f.point(P[0]));
  const double h = p.records<SectionKind::triangle_shells>()[t].h_plus;
  cams.push_back({"membrane-front", {C + N * (h + 250.0), C, perpendicular(N), 30}});
  // Grazing: the centre ray runs 14° below the tangent plane, the top rows just below it.
  cams.push_back({"grazing-membrane", {C + N * (0.5 * h) - T * 300.0, C + N * (0.5 * h - 75.0), N, 25}});
  dvec3 NV = glm::normalize(dvec3(normals[v[0]]));
  if (glm::dot(NV, n_out) < 0) NV = -NV;
  const dvec3 V = f.point(P[0]);
  NV = f.normal(NV);
  cams.push_back({"mesh-vertex", {V + NV * (h + 200.0), V, perpendicular(NV), 30}, true});
  // A Wang tile corner inside the triangle: the lattice point nearest the UV centroid.
  const float s = c.scales.y / c.scales.x;
  const glm::vec2 uvc = (uvs[v[0]] + uvs[v[1]] + uvs[v[2]]) / 3.0f;
  const glm::vec2 g = glm::round(uvc / s) * s;
  const gpu::TriangleChart chart = gpu::chart_make(glm::vec3(P[0]), glm::vec3(P[1]), glm::vec3(P[2]), uvs[v[0]], uvs[v[1]],
                                                   uvs[v[2]], glm::vec3(normals[v[0]]), glm::vec3(normals[v[1]]),
                                                   glm::vec3(normals[v[2]]));
  const dvec3 G = f.point(dvec3(gpu::chart_position(chart, g)));
  cams.push_back({"tile-corner", {G + N * (h + 200.0), G, perpendicular(N), 25}, true});
  const dvec3 prism_eye = clear_of_atoms(scene, C + N * (0.3 * h), T, glm::cross(N, T));
  cams.push_back({"inside-prism", {prism_eye, prism_eye - N * 150.0 + T * 150.0, N, 70}});
}

// Membrane cameras on the first instance with a membrane and a triangle that owns molecules.
void add_membrane_cameras(const format::Package& p, const ExplicitScene& scene, std::vector<VerifyCamera>& cams) {
  const auto comps = p.records<SectionKind::compartments>();
  const auto insts = p.records<SectionKind::compartment_instances>();
  const auto shells = p.records<SectionKind::triangle_shells>();
  for (std::uint32_t i = 0; i < insts.size(); ++i) {
    const gpu::Compartment& c = comps[insts[i].compartment];
    if (c.membrane_recipe == gpu::NANO_NO_INDEX || shells.empty()) continue;
    const std::uint32_t t = owning_triangle_mid_mesh(p.records<SectionKind::meshes>()[c.mesh], shells);
    if (t == gpu::NANO_NO_INDEX) continue;
    add_membrane_cameras(p, scene, i, t, cams);
    return;
  }
}

// The INSIDE box of c's core grid nearest the grid's middle (with `or_boundary`, a BOUNDARY box may
// do too), or -1.
std::int64_t core_box_nearest_middle(const gpu::Compartment& c, std::span<const std::uint8_t> occupancy, bool or_boundary) {
  const glm::uvec3 dims(c.grid_dims);
  const glm::ivec3 mid(dims / 2u);
  std::int64_t best = -1;
  double best_d = INFINITY;
  for (std::uint32_t k = 0; k < dims.z; ++k)
    for (std::uint32_t j = 0; j < dims.y; ++j)
      for (std::uint32_t a = 0; a < dims.x; ++a) {
        const std::uint32_t box = a + dims.x * (j + dims.y * k);
        const std::uint8_t occ = occupancy[c.grid_dims.w + box];
        if (occ != gpu::NANO_BOX_INSIDE && !(or_boundary && occ == gpu::NANO_BOX_BOUNDARY)) continue;
        const double d = glm::length(dvec3(glm::ivec3(a, j, k) - mid));
        if (d < best_d) best_d = d, best = box;
      }
  return best;
}

// The core cameras at `box` of instance `inst`'s core grid.
void add_core_cameras(const ExplicitScene& scene, const gpu::CompartmentInstance& inst, const gpu::Compartment& c,
                      std::uint32_t box, std::vector<VerifyCamera>& cams) {
  const glm::uvec3 dims(c.grid_dims);
  const glm::uvec3 ijk(box % dims.x, box / dims.x % dims.y, box / (dims.x * dims.y));
  const InstanceFrame f = frame_of(inst);
  const dvec3 centre_local = dvec3(c.grid_min) + double(c.grid_min.w) * (dvec3(ijk) + 0.5);
  const dvec3 E = f.point(centre_local);
  cams.push_back({"inside-core", {E, E + dvec3(1.0, 0.37, 0.21), dvec3(0, 0, 1), 60}});
  // Exactly axis-aligned through the grid: eye on a box corner plane, rays along +z.
  const dvec3 corner = f.point(dvec3(c.grid_min) + double(c.grid_min.w) * dvec3(ijk));
  cams.push_back({"axis-aligned-core", {corner, corner + dvec3(0, 0, 1), dvec3(0, 1, 0), 40}, true});
  // Inside an atom: the first atom of a copy near the box centre.
  dvec3 atom_centre(NAN);
  const double half = 0.5 * c.grid_min.w;
  scene.for_each_atom(WorldBox{E - half, E + half}, [&](const AtomSample& a) {
    if (std::isnan(atom_centre.x)) atom_centre = a.position;
  });
  if (!std::isnan(atom_centre.x))
    cams.push_back({"inside-atom", {atom_centre, atom_centre + dvec3(-0.3, 1.0, 0.45), dvec3(0, 0, 1), 60}});
}

// Core cameras on the last instance with a core grid that has an INSIDE box, at the INSIDE box
// nearest the grid's middle; only when no grid has one (a small virion's lumen is all BOUNDARY),
// at a BOUNDARY box. A BOUNDARY box of a small grid can put the eye outside its compartment,
// looking at whole cells the oracle cannot instantiate.
void add_core_cameras(const format::Package& p, const ExplicitScene& scene, std::vector<VerifyCamera>& cams) {
  const auto comps = p.records<SectionKind::compartments>();
  const auto insts = p.records<SectionKind::compartment_instances>();
  const auto occupancy = p.records<SectionKind::occupancy>();
  for (const bool or_boundary : {false, true})
    for (std::uint32_t i = std::uint32_t(insts.size()); i-- > 0;) {
      const gpu::Compartment& c = comps[insts[i].compartment];
      if (c.soluble_recipe == gpu::NANO_NO_INDEX) continue;
      const std::int64_t best = core_box_nearest_middle(c, occupancy, or_boundary);
      if (best < 0) continue;
      add_core_cameras(scene, insts[i], c, std::uint32_t(best), cams);
      return;
    }
}

// More views of the hard cases, each turned about its up axis by ±20°, ±40°, ..., up to `count`.
void add_turned_cameras(std::vector<VerifyCamera>& cams, std::size_t count) {
  const std::size_t hard = cams.size();
  for (std::size_t k = 0; cams.size() < count && hard > 0 && k < 8 * hard; ++k) {
    VerifyCamera extra = cams[k % hard];
    const double angle = (k % 2 == 0 ? 1.0 : -1.0) * 0.35 * double(1 + (k / hard) % 2);
    const glm::dvec3 off = extra.view.position - extra.view.look_at;
    const dvec3 axis = glm::normalize(extra.view.up);
    extra.view.position = extra.view.look_at + off * std::cos(angle) + glm::cross(axis, off) * std::sin(angle) +
                axis * glm::dot(axis, off) * (1 - std::cos(angle));
    extra.name += "-turned-" + std::to_string(k + 1);
    if (glm::length(glm::cross(glm::normalize(extra.view.look_at - extra.view.position), extra.view.up)) < 1e-3) continue;
    cams.push_back(extra);
  }
}

}  // namespace

std::vector<VerifyCamera> verify_cameras(const format::Package& p, const ExplicitScene& scene, std::size_t count) {
  std::vector<VerifyCamera> cams;
  add_membrane_cameras(p, scene, cams);
  add_core_cameras(p, scene, cams);
  add_turned_cameras(cams, count);
  if (cams.size() > count) cams.resize(count);
  return cams;
}

}  // namespace nano::oracle
