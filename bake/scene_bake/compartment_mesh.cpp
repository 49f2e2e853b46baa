#include "bake/scene_bake/compartment_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/box_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/uv_distortion.hpp"
#include "bake/scene_bake/mesh_packing.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {
namespace {

constexpr int kDefaultSphereTriangles = 1452;
constexpr int kDefaultRbcTriangles = 3000;

CompartmentMesh read_or_generate(const scene::MeshSource& source) {
  CompartmentMesh result;
  switch (source.kind) {
    case scene::MeshSource::Kind::file:
      result.mesh = mesh::read_proxy_mesh(source.file);
      result.origin = source.file.string();
      break;
    case scene::MeshSource::Kind::sphere: {
      const int n = source.triangles > 0 ? source.triangles : kDefaultSphereTriangles;
      result.mesh = mesh::make_sphere_mesh(n, source.radius);
      result.origin = "generated sphere (" + std::to_string(n) + " triangles)";
      break;
    }
    case scene::MeshSource::Kind::box: {
      result.mesh = mesh::make_box_mesh(source.box_size);
      result.origin = "generated box";
      break;
    }
    case scene::MeshSource::Kind::rbc: {
      const int n = source.triangles > 0 ? source.triangles : kDefaultRbcTriangles;
      result.mesh = mesh::make_rbc_mesh(n);
      result.origin = "generated red blood cell (" + std::to_string(n) + " triangles)";
      break;
    }
  }
  return result;
}

}  // namespace

void scale_mesh(mesh::ProxyMesh& mesh, double scale) {
  for (glm::dvec3& p : mesh.positions) p *= scale;
}

namespace {

[[noreturn]] void refuse(const CompartmentMesh& m, const std::string& compartment, const std::vector<mesh::MeshProblem>& list) {
  std::ostringstream problems;
  problems << "mesh is not usable for compartment '" << compartment << "':";
  for (const mesh::MeshProblem& p : list) {
    problems << "\n  ";
    if (p.face >= 0) problems << "face " << p.face << ": ";
    problems << p.rule << " (" << p.value << ")";
    if (!p.detail.empty()) problems << " " << p.detail;
  }
  // What "repair" did and left is half of why the mesh is still refused.
  if (m.repair) problems << "\n  " << mesh::describe(*m.repair);
  throw InputError(m.origin, "", problems.str());
}

// The enclosed volume by the divergence theorem (positive for an outward closed mesh).
double enclosed_volume(const mesh::ProxyMesh& m) {
  double v = 0;
  for (const mesh::Triangle& t : m.triangles)
    v += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
  return v;
}


// Where the stages below refuse the mesh from: its file (or what generated it), for this compartment.
InputSource mesh_source(const CompartmentMesh& result, const scene::CompartmentDescription& compartment) {
  return InputSource(result.origin, "compartment '" + compartment.name + "'");
}

// The repair stage: what "repair" mends, said in the report.
void repair(CompartmentMesh& result, const scene::CompartmentDescription& compartment) {
  result.repair = mesh::repair_mesh(result.mesh, mesh_source(result, compartment));
}

// The size stage: "diameter" or "volume" after the units and the compartment's scale.
void size(CompartmentMesh& result, const scene::CompartmentDescription& compartment) {
  const scene::MeshSource& source = compartment.mesh;
  double factor = 1.0;
  if (source.diameter) {
    factor = *source.diameter / mesh::largest_side(result.mesh);
  } else if (source.volume) {
    const double volume = enclosed_volume(result.mesh);
    if (!(volume > 0))
      throw InputError(result.origin, "", "\"volume\" needs a closed, outward mesh; this one encloses " + std::to_string(volume) +
                                              " Å³ (compartment '" + compartment.name + "')");
    factor = std::cbrt(*source.volume / volume);
  }
  scale_mesh(result.mesh, factor);
  result.scale *= factor;
}

mesh::RemeshPolicy remesh_policy(const scene::MeshSource& source) {
  mesh::RemeshPolicy policy;
  policy.mode = source.remesh == scene::MeshSource::Remesh::off     ? mesh::RemeshPolicy::Mode::off
                : source.remesh == scene::MeshSource::Remesh::edge ? mesh::RemeshPolicy::Mode::edge
                                                                   : mesh::RemeshPolicy::Mode::automatic;
  // The mesh's own UVs, kept as the scene asks, are not remeshed away.
  if (source.uv == scene::MeshSource::Uv::keep) policy.mode = mesh::RemeshPolicy::Mode::off;
  policy.edge = source.remesh_edge;
  return policy;
}

// The prepare and judge stages (bake/mesh/membrane_fit.hpp): remeshed when needed, refused with every
// place a bilayer cannot follow named, and the size at which it would (or the defect to mend).
void fit_for_membrane(CompartmentMesh& result, const scene::CompartmentDescription& compartment, double thickness) {
  const mesh::RemeshPolicy policy = remesh_policy(compartment.mesh);
  // Remeshing does not guess at a shape: a mesh that needs it is refused with all its own defects
  // (and what "repair" did), not only the first one fit_membrane would name.
  std::vector<mesh::MeshProblem> shape_problems;
  for (const mesh::MeshProblem& p : result.report.problems)
    if (!mesh::is_uv_rule(p.rule) && p.rule != mesh::rule::sliver) shape_problems.push_back(p);
  if (!shape_problems.empty() && mesh::remesh_needed(result.mesh, result.report, policy))
    refuse(result, compartment.name, shape_problems);
  const mesh::MembraneFit fit =
      mesh::fit_membrane(result.mesh, result.report, thickness, policy, mesh_source(result, compartment));
  result.remesh = fit.remesh;
  result.thinnest_wall = fit.thinnest_wall;
  result.narrowest_gap = fit.narrowest_gap;
  result.bilayer_thickness = thickness;
  if (!fit.fits())
    throw InputError(result.origin, "compartment '" + compartment.name + "' membrane",
                     mesh::describe_tight_features(fit, thickness, compartment.mesh.diameter, result.scale));
}

// The chart stage: the baker's UVs where the mesh has none usable (or the scene asks), then the
// mesh checked as the shells will use it.
void chart(CompartmentMesh& result, const scene::CompartmentDescription& compartment) {
  const scene::MeshSource& source = compartment.mesh;
  bool uv_trouble = !result.mesh.has_uvs();  // none read, or remeshed away (the fit checks the surface only)
  std::vector<mesh::MeshProblem> shape_problems;
  for (const mesh::MeshProblem& p : result.report.problems) {
    if (mesh::is_uv_rule(p.rule)) uv_trouble = true;
    else shape_problems.push_back(p);
  }
  const bool generate = source.uv == scene::MeshSource::Uv::generate ||
                        (source.uv == scene::MeshSource::Uv::automatic && uv_trouble);
  if (!generate) {
    if (!result.report.usable()) refuse(result, compartment.name, result.report.problems);
    result.uv_origin = "from the mesh";
    return;
  }
  // Charts need a sound surface: report its own problems first, not their consequences for UVs.
  if (!shape_problems.empty()) refuse(result, compartment.name, shape_problems);
  result.uv_origin = source.uv == scene::MeshSource::Uv::generate ? "made by the baker (the scene asks \"uv\": \"generate\")"
                     : result.mesh.has_uvs()                       ? "made by the baker (the mesh's own UVs fail the checks)"
                     : result.remesh                               ? "made by the baker (the mesh was remeshed)"
                                                                   : "made by the baker (the mesh has none)";
  result.charts = mesh::generate_uv_charts(result.mesh, mesh_source(result, compartment));
  result.report = mesh::check_mesh(result.mesh, mesh::CheckOptions{});
  if (!result.report.usable()) refuse(result, compartment.name, result.report.problems);
}

}  // namespace

CompartmentMesh load_compartment_mesh(const scene::CompartmentDescription& compartment,
                                      std::optional<double> bilayer_thickness,
                                      const std::function<void(const mesh::ProxyMesh&)>& check_size, MeshStage until) {
  CompartmentMesh result = read_or_generate(compartment.mesh);
  result.scale = compartment.mesh.unit * compartment.scale;
  scale_mesh(result.mesh, result.scale);
  // Repair before a target size: a volume needs the holes closed.
  if (compartment.mesh.repair) repair(result, compartment);
  size(result, compartment);
  if (check_size) check_size(result.mesh);
  result.report = mesh::check_mesh(result.mesh, mesh::CheckOptions{});
  if (bilayer_thickness) fit_for_membrane(result, compartment, *bilayer_thickness);
  if (until == MeshStage::judged) return result;
  chart(result, compartment);
  return result;
}

scene::CompartmentMeasure measure_compartment(const mesh::ProxyMesh& mesh) {
  scene::CompartmentMeasure m;
  for (const glm::dvec3& p : mesh.positions) m.extent = std::max(m.extent, glm::length(p));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) m.area += mesh::world_area(mesh, t);
  m.volume = enclosed_volume(mesh);
  m.triangles = mesh.triangles.size();
  return m;
}

void put_on_storage_grids(CompartmentMesh& m) {
  mesh::ProxyMesh moved = on_storage_grids(m.mesh);
  const mesh::MeshReport report = mesh::check_mesh(moved, mesh::CheckOptions{});
  if (!report.usable()) {
    const mesh::MeshProblem& p = report.problems.front();
    m.storage = "kept exact, stored with zstd: on Draco's grids it would fail " + p.rule +
                (p.face >= 0 ? " at face " + std::to_string(p.face) : std::string());
    return;
  }
  char step[32];
  std::snprintf(step, sizeof step, "%g", double(storage_position_step(m.mesh)));
  m.storage = std::string("on Draco's grids: positions to multiples of ") + step +
              " Å, normals to 16-bit octahedral pairs, UVs to multiples of 2^-24";
  m.mesh = std::move(moved);
  m.report = report;
  m.on_storage_grids = true;
}

}  // namespace nano::scene_bake
