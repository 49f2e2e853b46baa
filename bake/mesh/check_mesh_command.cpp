// nanobake check-mesh MESH [--json] [--tile-size S] [--make-uvs OUT.obj]
#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "bake/commands.hpp"
#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/uv_charts.hpp"

namespace nano::bake {

void add_check_mesh_command(CLI::App& app) {
  struct Arguments {
    std::string mesh;
    bool json = false;
    std::optional<double> tile_size;
    std::string make_uvs;
    std::size_t max_triangles = mesh::CheckOptions{}.max_triangles;
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
  command->callback([args] {
    mesh::ProxyMesh proxy = mesh::read_proxy_mesh(args->mesh);
    mesh::CheckOptions options;
    options.tile_size = args->tile_size;
    options.max_triangles = args->max_triangles;
    mesh::MeshReport report = mesh::check_mesh(proxy, options);
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
