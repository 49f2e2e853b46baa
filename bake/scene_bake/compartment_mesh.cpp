#include "bake/scene_bake/compartment_mesh.hpp"

#include <sstream>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"

namespace nano::bake {
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

CompartmentMesh load_compartment_mesh(const scene::CompartmentDescription& compartment) {
  CompartmentMesh result = read_or_generate(compartment.mesh);
  scale_mesh(result.mesh, compartment.scale);
  result.report = mesh::check_mesh(result.mesh, mesh::CheckOptions{});
  if (!result.report.usable()) {
    std::ostringstream problems;
    problems << "mesh is not usable for compartment '" << compartment.name << "':";
    for (const mesh::MeshProblem& p : result.report.problems) {
      problems << "\n  ";
      if (p.face >= 0) problems << "face " << p.face << ": ";
      problems << p.rule << " (" << p.value << ")";
      if (!p.detail.empty()) problems << " " << p.detail;
    }
    throw InputError(result.origin, "", problems.str());
  }
  return result;
}

}  // namespace nano::bake
