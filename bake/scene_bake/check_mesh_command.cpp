// nanobake check-mesh MESH [--json] [--tile-size S] [--make-uvs OUT.obj]
//                         [--diameter D | --scale F | --scene SCENE.json] ...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "bake/commands.hpp"
#include "bake/mesh/membrane_fit.hpp"
#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/uv_charts.hpp"
#include "bake/scene/scene_parser.hpp"
#include "bake/scene_bake/compartment_mesh.hpp"
#include "bake/scene_bake/scene_baker.hpp"
#include "common/error.hpp"

namespace nano::bake {

namespace {

struct Arguments {
  std::string mesh;
  bool json = false;
  std::optional<double> tile_size;
  std::string make_uvs;
  std::size_t max_triangles = mesh::CheckOptions{}.max_triangles;
  std::optional<double> diameter, scale;
  std::string units = "A";
  bool repair = false;
  std::string remesh = "auto";
  double bilayer = mesh::kDefaultBilayerThickness;
  std::string scene, compartment;
  std::string write_prepared;
  bool judges() const { return diameter || scale || !scene.empty(); }
};

// The compartment the scene names (or its only one with a mesh file), with the bilayer the bake
// would line it with.
std::pair<scene::CompartmentDescription, std::optional<double>> scene_compartment(const Arguments& args) {
  const scene::SceneDescription scene = scene::load_scene_description(args.scene);
  std::optional<std::size_t> found;
  for (std::size_t c = 0; c < scene.compartments.size(); ++c) {
    const scene::CompartmentDescription& compartment = scene.compartments[c];
    if (!args.compartment.empty() ? compartment.name == args.compartment
                                  : compartment.mesh.kind == scene::MeshSource::Kind::file && !found)
      found = c;
  }
  if (!found)
    throw InputError(args.scene, args.compartment.empty() ? "compartments" : "compartments." + args.compartment,
                     args.compartment.empty() ? "no compartment with a mesh file; name one with --compartment"
                                              : "no such compartment");
  return {scene.compartments[*found], scene_bake::compartment_bilayer_thickness(scene, *found)};
}

// --remesh's edge, read where the option's name is known (a scene's "remesh" edge: likewise > 0).
double remesh_edge(const std::string& text) {
  char* end = nullptr;
  const double edge = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(edge > 0 && std::isfinite(edge)))
    InputSource("--remesh").fail("expected auto, off or an edge in Å > 0, got '" + text + "'");
  return edge;
}

// The compartment the command line describes: MESH sized and mended as a scene's keys would.
scene::CompartmentDescription command_line_compartment(const Arguments& args) {
  scene::CompartmentDescription c;
  c.name = "check-mesh";
  c.mesh.file = args.mesh;
  c.mesh.unit = args.units == "nm" ? 10.0 : args.units == "um" ? 1e4 : 1.0;
  c.mesh.diameter = args.diameter;
  if (args.scale) c.scale = *args.scale;
  c.mesh.repair = args.repair;
  if (args.remesh == "off") {
    c.mesh.remesh = scene::MeshSource::Remesh::off;
  } else if (args.remesh != "auto") {
    c.mesh.remesh = scene::MeshSource::Remesh::edge;
    c.mesh.remesh_edge = remesh_edge(args.remesh);
  }
  return c;
}

// check-mesh --diameter/--scale/--scene: the bake's mesh stages (compartment_mesh.hpp) up to and
// including the charts (which refuse what the shells could not use), the same verdict and numbers.
void judge_membrane_fit(const Arguments& args) {
  scene::CompartmentDescription compartment;
  std::optional<double> thickness = args.bilayer;
  if (!args.scene.empty()) std::tie(compartment, thickness) = scene_compartment(args);
  else compartment = command_line_compartment(args);
  const std::string file = compartment.mesh.kind == scene::MeshSource::Kind::file ? compartment.mesh.file.string() : args.mesh;
  scene_bake::CompartmentMesh prepared;
  try {
    prepared = scene_bake::load_compartment_mesh(compartment, thickness, {}, scene_bake::MeshStage::charted);
  } catch (const InputError& e) {
    std::fputs((std::string(e.what()) + "\n").c_str(), stdout);
    std::fflush(stdout);
    throw CLI::RuntimeError(1);
  }
  std::string text;
  if (prepared.repair) text += file + ": " + mesh::describe(*prepared.repair) + "\n";
  if (prepared.remesh) text += file + ": " + mesh::describe(*prepared.remesh) + "\n";
  if (thickness) {
    char line[240];
    std::snprintf(line, sizeof line, ": a bilayer %.1f Å thick fits (thinnest wall %.1f Å, narrowest gap %.1f Å; %zu triangles)\n",
                  *thickness, prepared.thinnest_wall, prepared.narrowest_gap, prepared.mesh.triangles.size());
    text += file + line;
  }
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  if (!args.write_prepared.empty()) mesh::write_obj(args.write_prepared, prepared.mesh);
}

// The mesh file's own checks (closed, manifold, UVs...), and the charts a scene would get.
void check_proxy_mesh(const Arguments& args) {
  mesh::ProxyMesh proxy = mesh::read_proxy_mesh(args.mesh);
  mesh::CheckOptions options;
  options.tile_size = args.tile_size;
  options.max_triangles = args.max_triangles;
  mesh::MeshReport report = mesh::check_mesh(proxy, options);
  // The charts a scene would get ("uv": "auto"), when nothing but the UVs is wrong, or those
  // --make-uvs asks for.
  const bool surface_sound = std::all_of(report.problems.begin(), report.problems.end(),
                                         [](const mesh::MeshProblem& p) { return mesh::is_uv_rule(p.rule); });
  const bool make = !args.make_uvs.empty();
  std::optional<mesh::ChartAtlas> atlas;
  mesh::ProxyMesh charted = proxy;
  if (surface_sound && (make || !report.usable())) {
    atlas = mesh::generate_uv_charts(charted, args.mesh);
    if (make) report = mesh::check_mesh(charted, options);
  }
  std::string text = args.json ? [&] {
    nlohmann::json j = mesh::report_to_json(report);
    if (atlas) j["baker_charts"] = mesh::to_json(*atlas);
    return j.dump(2) + "\n";
  }()
                                : mesh::report_to_text(report, args.mesh);
  if (atlas && !args.json) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "%s: the baker %s UVs: %zu charts, seam %.4g (mesh units), stretch max %.3f (mean %.3f), %.2f s\n",
                  args.mesh.c_str(), args.make_uvs.empty() ? "would make (scene \"uv\": \"auto\")" : "made", atlas->charts.size(),
                  atlas->seam_length, atlas->max_stretch, atlas->mean_stretch, atlas->seconds);
    text += line;
  }
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  if (!args.make_uvs.empty() && atlas && report.usable()) mesh::write_obj(args.make_uvs, charted);
  if (!report.usable()) throw CLI::RuntimeError(1);
}

}  // namespace

void add_check_mesh_command(CLI::App& app) {
  auto args = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "check-mesh",
      "Check that a proxy mesh (OBJ/PLY/OFF/STL/Draco/Collada) is usable for the membrane shell: closed, manifold, outward, "
      "no degenerate or sliver triangles, UVs in [0,1] without zero-area or flipped triangles; reports seams, "
      "UV distortion, the UV scale k and the replication area. Face indices are 0-based triangles in file "
      "order. Exit 0 when usable, 1 with the list of every problem.");
  command->add_option("mesh", args->mesh, "mesh file (.obj, .ply, .off, .stl, .drc, .dae); not with --scene");
  command->add_option("--make-uvs", args->make_uvs,
                      "replace the mesh's UVs by the charts the baker makes, check that, and write it as OBJ");
  command->add_flag("--json", args->json, "print the report as JSON");
  command->add_option("--max-triangles", args->max_triangles, "refuse a mesh of more triangles")->capture_default_str();
  command->add_option("--tile-size", args->tile_size,
                      "world size S of one Wang tile (default k/20: 20 tiles across the unit UV square)")
      ->check(CLI::PositiveNumber);
  auto* diameter = command->add_option("--diameter", args->diameter,
                                       "size the mesh as a scene's \"diameter\" does (Å: its largest bounding-box side) and "
                                       "judge whether a bilayer fits it: the bake's own stages (repair, remeshing, judgement) "
                                       "stopped after the judgement, the same verdict and numbers")
                       ->check(CLI::PositiveNumber);
  auto* scale = command->add_option("--scale", args->scale, "the same with a scene's \"scale\" (Å per mesh unit)")
                    ->check(CLI::PositiveNumber)
                    ->excludes(diameter);
  command->add_option("--units", args->units, "with --diameter or --scale: the file's unit, as a scene's \"units\"")
      ->check(CLI::IsMember({"A", "nm", "um"}))
      ->capture_default_str();
  command->add_flag("--repair", args->repair, "with --diameter or --scale: mend the mesh first, as a scene's \"repair\": true");
  command->add_option("--remesh", args->remesh,
                      "with --diameter or --scale: auto (default), off, or an edge in Å, as a scene's \"remesh\"")
      ->capture_default_str();
  command->add_option("--bilayer", args->bilayer,
                      "with --diameter or --scale: the membrane's thickness, Å (default: a POPC bilayer's, the bake report's "
                      "bilayer_thickness_A for a scene of POPC)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  auto* scene = command->add_option("--scene", args->scene,
                                    "judge the mesh of a compartment of this scene exactly as its bake would (its mesh keys "
                                    "and its membrane's bilayer); MESH is then ignored")
                    ->excludes(diameter)
                    ->excludes(scale);
  command->add_option("--compartment", args->compartment, "with --scene: the compartment (default: its first with a mesh file)")
      ->needs(scene);
  command->add_option("--write-prepared", args->write_prepared,
                      "with --diameter, --scale or --scene: write the mesh as the baker would shell it (sized, repaired, "
                      "remeshed if needed, charted) as OBJ");
  command->callback([args] {
    if (args->mesh.empty() && args->scene.empty()) throw CLI::RequiredError("mesh (or --scene)");
    if (args->judges()) {
      judge_membrane_fit(*args);
      return;
    }
    check_proxy_mesh(*args);
  });
}

}  // namespace nano::bake
