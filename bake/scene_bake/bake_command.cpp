// `nanobake bake SCENE.json -o SCENE.nup` (also `nanobake SCENE.json -o ...`): the whole pipeline.
#include <cstdio>
#include <fstream>

#include "bake/commands.hpp"
#include "bake/scene/scene_parser.hpp"
#include "bake/scene_bake/bake_report.hpp"
#include "bake/scene_bake/scene_baker.hpp"
#include "common/atomic_file.hpp"
#include "format/validator.hpp"

namespace nano::bake {

void add_bake_command(CLI::App& app) {
  struct Options {
    std::string scene, output, report;
    std::uint64_t seed = 0;
    int jobs = 2;
    MeshCodec mesh_codec = MeshCodec::automatic;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("bake", "Bake a scene description into a package (also: nanobake SCENE.json -o PKG)");
  cmd->add_option("scene", options->scene, "scene description (scene.json)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", options->output, "package to write (.nup)")->required();
  CLI::Option* seed = cmd->add_option("--seed", options->seed, "overrides the scene's seed");
  cmd->add_option("--jobs", options->jobs, "worker threads")->check(CLI::Range(1, 256));
  cmd->add_option("--report", options->report, "write a JSON report of what was baked");
  cmd->add_option("--mesh-codec", options->mesh_codec,
                  "mesh sections: auto (Draco where smaller than zstd, meshes on Draco's exact grids), draco, or zstd "
                  "(meshes exactly as read)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, MeshCodec>{
          {"auto", MeshCodec::automatic}, {"draco", MeshCodec::draco}, {"zstd", MeshCodec::zstd}}));
  cmd->callback([options, seed] {
    const scene::SceneDescription scene = scene::load_scene_description(options->scene);
    BakeOptions bake_options;
    if (seed->count() > 0) bake_options.seed = options->seed;
    bake_options.jobs = options->jobs;
    bake_options.mesh_codec = options->mesh_codec;
    bake_options.progress = [](const std::string& stage) { std::fprintf(stderr, "nanobake: %s...\n", stage.c_str()); };
    const BakedScene baked = bake_scene(scene, bake_options);
    const auto sections = baked.content.sections();
    const std::vector<std::byte> bytes = format::build_package(sections);
    // Trust nothing, not even ourselves: the package must pass the full validator before it is
    // written, so an invalid package never reaches the disk.
    const format::Package package = format::Package::from_bytes(bytes, options->output);
    format::validate_semantics(package);
    write_file_atomically(options->output, bytes);
    std::fputs(bake_summary(baked, package).c_str(), stdout);
    if (!options->report.empty()) {
      const std::string text = bake_report(baked, package).dump(2) + "\n";
      write_file_atomically(options->report, std::as_bytes(std::span(text.data(), text.size())));
    }
  });
}

}  // namespace nano::bake
