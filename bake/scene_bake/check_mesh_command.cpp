// nanobake check-mesh MESH [--json] [--tile-size S] [--make-uvs OUT.obj]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "bake/commands.hpp"
#include "bake/mesh/membrane_fit.hpp"
#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/uv_charts.hpp"

namespace nano::bake {

namespace {

// What a scene's membrane without a patch of its own measures, and a POPC bilayer's headgroup to headgroup.
constexpr double kDefaultBilayerThickness = 40.0;


// check-mesh --diameter/--scale: the baker's verdict (mesh::fit_membrane) without baking.
template <class Arguments>
void judge_membrane_fit(mesh::ProxyMesh& proxy, mesh::MeshReport& report, const Arguments& args) {
  const double factor = args.diameter ? *args.diameter / mesh::largest_side(proxy) : *args.scale;
  for (glm::dvec3& p : proxy.positions) p *= factor;
  report = mesh::check_mesh(proxy, mesh::CheckOptions{});
  mesh::MembraneFit fit;
  try {
    fit = mesh::fit_membrane(proxy, report, args.bilayer, mesh::RemeshPolicy{});
  } catch (const std::invalid_argument& e) {
    std::fputs((args.mesh + ": " + e.what() + "\n" + mesh::report_to_text(report, args.mesh)).c_str(), stdout);
    throw CLI::RuntimeError(1);
  }
  std::string text;
  if (fit.remesh) text += args.mesh + ": " + mesh::describe(*fit.remesh) + "\n";
  if (!fit.fits()) {
    text += args.mesh + ": " + mesh::describe_tight_features(fit, args.bilayer, args.diameter) + "\n";
    if (!args.diameter)
      text += args.mesh + ": that is \"scale\": " + std::to_string(*args.scale * fit.scale_needed) + " or more\n";
  } else {
    char line[200];
    std::snprintf(line, sizeof line, ": a bilayer %.1f Å thick fits (thinnest wall %.1f Å, narrowest gap %.1f Å)\n", args.bilayer,
                  fit.thinnest_wall, fit.narrowest_gap);
    text += args.mesh + line;
  }
  const std::vector<mesh::MeshProblem> shape = [&] {
    std::vector<mesh::MeshProblem> list;
    for (const mesh::MeshProblem& p : report.problems)
      if (!mesh::is_uv_rule(p.rule)) list.push_back(p);
    return list;
  }();
  if (!shape.empty()) text += mesh::report_to_text(report, args.mesh);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  if (!args.write_prepared.empty() && fit.fits() && shape.empty()) mesh::write_obj(args.write_prepared, proxy);
  if (!fit.fits() || !shape.empty()) throw CLI::RuntimeError(1);
}

}  // namespace

void add_check_mesh_command(CLI::App& app) {
  struct Arguments {
    std::string mesh;
    bool json = false;
    std::optional<double> tile_size;
    std::string make_uvs;
    std::size_t max_triangles = mesh::CheckOptions{}.max_triangles;
    std::optional<double> diameter, scale;
    double bilayer = kDefaultBilayerThickness;
    std::string write_prepared;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "check-mesh",
      "Check that a proxy mesh (OBJ/PLY/OFF/STL/Draco) is usable for the membrane shell: closed, manifold, outward, "
      "no degenerate or sliver triangles, UVs in [0,1] without zero-area or flipped triangles; reports seams, "
      "UV distortion, the UV scale k and the replication area. Face indices are 0-based triangles in file "
      "order. Exit 0 when usable, 1 with the list of every problem.");
  command->add_option("mesh", args->mesh, "mesh file (.obj, .ply, .off, .stl, .drc)")->required();
  command->add_option("--make-uvs", args->make_uvs,
                      "replace the mesh's UVs by the charts the baker makes, check that, and write it as OBJ");
  command->add_flag("--json", args->json, "print the report as JSON");
  command->add_option("--max-triangles", args->max_triangles, "refuse a mesh of more triangles")->capture_default_str();
  command->add_option("--tile-size", args->tile_size,
                      "world size S of one Wang tile (default k/20: 20 tiles across the unit UV square)")
      ->check(CLI::PositiveNumber);
  auto* diameter = command->add_option("--diameter", args->diameter,
                                       "size the mesh as a scene's \"diameter\" does (Å: its largest bounding-box side) and "
                                       "judge whether a bilayer fits it, as the baker would (remeshing it if needed)")
                       ->check(CLI::PositiveNumber);
  command->add_option("--scale", args->scale, "the same with a scene's \"scale\" (Å per mesh unit)")
      ->check(CLI::PositiveNumber)
      ->excludes(diameter);
  command->add_option("--bilayer", args->bilayer,
                      "with --diameter or --scale: the membrane's thickness, Å (the bake report's bilayer_thickness_A)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--write-prepared", args->write_prepared,
                      "with --diameter or --scale: write the mesh as the baker would shell it (sized, remeshed if needed) as OBJ");
  command->callback([args] {
    mesh::ProxyMesh proxy = mesh::read_proxy_mesh(args->mesh);
    mesh::CheckOptions options;
    options.tile_size = args->tile_size;
    options.max_triangles = args->max_triangles;
    mesh::MeshReport report = mesh::check_mesh(proxy, options);
    if (args->diameter || args->scale) {
      judge_membrane_fit(proxy, report, *args);
      return;
    }
    // The charts a scene would get ("uv": "auto"), when nothing but the UVs is wrong, or those
    // --make-uvs asks for.
    const bool surface_sound = std::all_of(report.problems.begin(), report.problems.end(),
                                           [](const mesh::MeshProblem& p) { return mesh::is_uv_rule(p.rule); });
    const bool make = !args->make_uvs.empty();
    std::optional<mesh::ChartAtlas> atlas;
    mesh::ProxyMesh charted = proxy;
    if (surface_sound && (make || !report.usable())) {
      atlas = mesh::generate_uv_charts(charted);
      if (make) report = mesh::check_mesh(charted, options);
    }
    std::string text = args->json ? [&] {
      nlohmann::json j = mesh::report_to_json(report);
      if (atlas) j["baker_charts"] = mesh::to_json(*atlas);
      return j.dump(2) + "\n";
    }()
                                  : mesh::report_to_text(report, args->mesh);
    if (atlas && !args->json) {
      char line[400];
      std::snprintf(line, sizeof line,
                    "%s: the baker %s UVs: %zu charts, seam %.4g (mesh units), stretch max %.3f (mean %.3f), %.2f s\n",
                    args->mesh.c_str(), args->make_uvs.empty() ? "would make (scene \"uv\": \"auto\")" : "made", atlas->charts.size(),
                    atlas->seam_length, atlas->max_stretch, atlas->mean_stretch, atlas->seconds);
      text += line;
    }
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    if (!args->make_uvs.empty() && atlas && report.usable()) mesh::write_obj(args->make_uvs, charted);
    if (!report.usable()) throw CLI::RuntimeError(1);
  });
}

}  // namespace nano::bake
