// Explicit instancing of one box of a package must be clash-free: every atom virtual instancing
// places there keeps 0.6 × (r1 + r2) from every atom of another copy.
//   box_clashes PKG box XMIN YMIN ZMIN XMAX YMAX ZMAX MIN_COPIES
//   box_clashes PKG membrane INSTANCE HALF_SIZE MIN_COPIES   box around the instance's first mesh vertex
//   box_clashes PKG core INSTANCE HALF_SIZE MIN_COPIES       box around the instance's middle INSIDE core box
//                                                           (or the most central BOUNDARY box)
//   box_clashes PKG where INSTANCE HALF_SIZE       prints the membrane box ("x0,y0,z0,x1,y1,z1"), checks nothing
//   box_clashes PKG vertices INSTANCE HALF_SIZE COUNT MIN_COPIES
//                                    boxes around COUNT mesh vertices spread over the vertex list
//                                    (rims, dimples, chart corners and seams alike), each checked
// Exit 0 when clash-free and at least MIN_COPIES copies were found in every box (an empty box
// cannot pass).
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "format/package_view.hpp"
#include "format/validator.hpp"
#include "runtime/oracle/clash_check.hpp"
#include "runtime/oracle/explicit_scene.hpp"

namespace {

using nano::format::SectionKind;

glm::dvec3 to_world(const nano::gpu::CompartmentInstance& instance, const glm::dvec3& p) {
  const nano::format::InstanceTransform t = nano::format::instance_transform(instance);
  return t.linear * p + t.translation;
}

// A compartment-space point of the instance's membrane or core, chosen from the package itself.
glm::dvec3 sample_point(const nano::format::Package& package, const nano::gpu::CompartmentInstance& instance,
                        const std::string& where) {
  const auto& compartment = package.records<SectionKind::compartments>()[instance.compartment];
  if (where == "membrane") {
    const auto& mesh = package.records<SectionKind::meshes>()[compartment.mesh];
    return glm::dvec3(glm::vec3(package.records<SectionKind::vertex_positions>()[mesh.first_vertex]));
  }
  const glm::uvec3 dims(compartment.grid_dims);
  const auto occupancy = package.records<SectionKind::occupancy>().subspan(compartment.grid_dims.w);
  // The middle INSIDE box; a small compartment may have none, then the BOUNDARY box nearest the
  // grid's centre (its molecules are kept by mask).
  std::vector<std::uint64_t> inside;
  std::uint64_t nearest = 0;
  double nearest_d2 = 1e300;
  const glm::dvec3 middle = (glm::dvec3(dims) - 1.0) * 0.5;
  const auto ijk_of = [&](std::uint64_t i) {
    return glm::dvec3(i % dims.x, (i / dims.x) % dims.y, i / (std::uint64_t(dims.x) * dims.y));
  };
  for (std::uint64_t i = 0; i < std::uint64_t(dims.x) * dims.y * dims.z; ++i) {
    if (occupancy[i] == nano::gpu::NANO_BOX_INSIDE) inside.push_back(i);
    if (occupancy[i] == nano::gpu::NANO_BOX_BOUNDARY) {
      const glm::dvec3 d = ijk_of(i) - middle;
      if (glm::dot(d, d) < nearest_d2) {
        nearest_d2 = glm::dot(d, d);
        nearest = i;
      }
    }
  }
  if (inside.empty() && nearest_d2 == 1e300) throw std::runtime_error("compartment has no core box that holds molecules");
  const glm::dvec3 ijk = ijk_of(inside.empty() ? nearest : inside[inside.size() / 2]);
  return glm::dvec3(glm::vec3(compartment.grid_min)) + (ijk + 0.5) * double(compartment.grid_min.w);
}

// Explicitly instances one box and reports its clashes; true when clash-free with enough copies.
bool check_box(const std::string& path, const nano::oracle::ExplicitScene& scene, const nano::oracle::WorldBox& box,
               std::size_t min_copies) {

  std::vector<nano::oracle::ClashAtom> atoms;
  std::set<std::uint64_t> copies;
  std::map<std::uint64_t, std::string> names;  // for the clash report: which copies, where
  scene.for_each_atom(box, [&](const nano::oracle::AtomSample& a) {
    atoms.push_back({a.copy->number, a.position, a.radius});
    if (copies.insert(a.copy->number).second) {
      const nano::oracle::CopyId& id = a.copy->id;
      char text[160];
      std::snprintf(text, sizeof text, "%s %u cell (%d %d %d) #%u type %u",
                    id.kind == nano::oracle::CopyKind::membrane ? "triangle" : "box", id.element, id.cell.x,
                    id.cell.y, id.cell.z, id.instance, a.copy->molecule_type);
      names[a.copy->number] = text;
    }
  });
  const nano::oracle::ClashReport report = nano::oracle::find_clashes(atoms);
  std::printf("%s [%.0f %.0f %.0f]-[%.0f %.0f %.0f]: %zu copies, %zu atoms, %llu clashing pairs\n", path.c_str(), box.min.x,
              box.min.y, box.min.z, box.max.x, box.max.y, box.max.z, copies.size(), atoms.size(),
              static_cast<unsigned long long>(report.count));
  for (std::size_t i = 0; i < report.pairs.size() && i < 10; ++i) {
    const auto& c = report.pairs[i];
    std::printf("  [%s] and [%s]: %.3f Å < %.3f Å\n", names[atoms[c.a].copy].c_str(), names[atoms[c.b].copy].c_str(),
                c.distance, c.limit);
  }
  return report.count == 0 && copies.size() >= min_copies;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 2 ? argv[2] : "";
  if (!((mode == "box" && argc == 10) || ((mode == "membrane" || mode == "core") && argc == 6) || (mode == "where" && argc == 5) ||
        (mode == "vertices" && argc == 7))) {
    std::fprintf(stderr, "usage: box_clashes PKG box XMIN YMIN ZMIN XMAX YMAX ZMAX MIN_COPIES\n"
                         "       box_clashes PKG membrane|core INSTANCE HALF_SIZE MIN_COPIES\n"
                         "       box_clashes PKG where INSTANCE HALF_SIZE\n"
                         "       box_clashes PKG vertices INSTANCE HALF_SIZE COUNT MIN_COPIES\n");
    return 2;
  }
  const nano::format::Package package = nano::format::open_validated(argv[1]);
  const nano::oracle::ExplicitScene scene(package);
  nano::oracle::WorldBox box;
  if (mode == "box") {
    box.min = {std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5])};
    box.max = {std::atof(argv[6]), std::atof(argv[7]), std::atof(argv[8])};
  } else if (mode != "vertices") {
    const auto instance = package.records<SectionKind::compartment_instances>()[std::strtoul(argv[3], nullptr, 10)];
    const glm::dvec3 centre = to_world(instance, sample_point(package, instance, mode == "where" ? "membrane" : mode));
    const double half = std::atof(argv[4]);
    box.min = centre - half;
    box.max = centre + half;
  }
  if (mode == "where") {
    std::printf("%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z);
    return 0;
  }
  const std::size_t min_copies = std::strtoull(argv[argc - 1], nullptr, 10);
  if (mode != "vertices") return check_box(argv[1], scene, box, min_copies) ? 0 : 1;
  const auto instance = package.records<SectionKind::compartment_instances>()[std::strtoul(argv[3], nullptr, 10)];
  const auto& compartment = package.records<SectionKind::compartments>()[instance.compartment];
  const auto& mesh = package.records<SectionKind::meshes>()[compartment.mesh];
  const auto positions = package.records<SectionKind::vertex_positions>().subspan(mesh.first_vertex, mesh.vertex_count);
  const double half = std::atof(argv[4]);
  const std::size_t count = std::max<std::size_t>(1, std::strtoull(argv[5], nullptr, 10));
  bool all = true;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 centre = to_world(instance, glm::dvec3(glm::vec3(positions[i * positions.size() / count])));
    all = check_box(argv[1], scene, {centre - half, centre + half}, min_copies) && all;
  }
  return all ? 0 : 1;
}
