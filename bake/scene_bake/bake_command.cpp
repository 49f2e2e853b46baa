// `nanobake bake SCENE.json -o SCENE.nup` (also `nanobake SCENE.json -o ...`): the whole pipeline.
#include <chrono>
#include <cstdio>
#include <fstream>

#include "bake/commands.hpp"
#include "bake/scene/scene_parser.hpp"
#include "bake/scene_bake/bake_estimate.hpp"
#include "bake/scene_bake/bake_progress.hpp"
#include "bake/scene_bake/bake_report.hpp"
#include "bake/scene_bake/scene_baker.hpp"
#include "common/atomic_file.hpp"
#include "format/validator.hpp"

namespace nano::bake {
// The command drives the pipeline of bake/scene_bake.
using namespace nano::scene_bake;

void add_bake_command(CLI::App& app) {
  struct Options {
    std::string scene, output, report;
    std::uint64_t seed = 0;
    int jobs = 2;
    std::string max_memory;
    bool dry_run = false, quiet = false;
    MeshCodec mesh_codec = MeshCodec::automatic;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("bake", "Bake a scene description into a package (also: nanobake SCENE.json -o PKG)");
  cmd->add_option("scene", options->scene, "scene description (scene.json)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", options->output, "package to write (.nup)")->required();
  CLI::Option* seed = cmd->add_option("--seed", options->seed, "overrides the scene's seed");
  cmd->add_option("--jobs", options->jobs, "worker threads")->check(CLI::Range(1, 256));
  cmd->add_option("--report", options->report, "write a JSON report of what was baked");
  cmd->add_flag("--dry-run", options->dry_run,
                "check the scene and print the estimated time, peak memory and copy counts, without baking");
  cmd->add_option("--max-memory", options->max_memory,
                  "refuse a bake whose estimated peak memory passes this (e.g. 8G, 512M; default: what the machine has available)");
  cmd->add_flag("-q,--quiet", options->quiet, "print no progress");
  cmd->add_option("--mesh-codec", options->mesh_codec,
                  "mesh sections: auto (Draco where smaller than zstd, meshes on Draco's exact grids), draco, or zstd "
                  "(meshes exactly as read)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, MeshCodec>{
          {"auto", MeshCodec::automatic}, {"draco", MeshCodec::draco}, {"zstd", MeshCodec::zstd}}));
  cmd->callback([options, seed] {
    remove_temporaries_on_interrupt();
    const scene::SceneDescription scene = scene::load_scene_description(options->scene);
    BakeOptions bake_options;
    if (seed->count() > 0) bake_options.seed = options->seed;
    bake_options.jobs = options->jobs;
    bake_options.mesh_codec = options->mesh_codec;
    bake_options.estimate_only = options->dry_run;
    if (!options->max_memory.empty()) {
      bake_options.max_memory = parse_byte_size(options->max_memory);
      if (!bake_options.max_memory)
        throw CLI::ValidationError("--max-memory", "expected a size such as 8G, 512M or 2000000000, got " + options->max_memory);
    } else if (const double available = available_memory_bytes(); available > 0.0) {
      bake_options.max_memory = available;
    }
    ProgressDisplay display(options->quiet ? ProgressDisplay::Mode::quiet : ProgressDisplay::mode_for(stderr), stderr);
    bake_options.on_stage_begin = [&display](const std::string& stage) { display.begin(stage); };
    bake_options.on_stage_end = [&display](const std::string& stage, double seconds) { display.end(stage, seconds); };
    const BakedScene baked = bake_scene(scene, bake_options);
    if (options->dry_run) {
      std::fputs(describe(baked.estimate).c_str(), stdout);
      return;
    }
    display.begin("writing the package");
    const auto written = std::chrono::steady_clock::now();
    const auto sections = baked.content.sections();
    const std::vector<std::byte> bytes = format::build_package(sections);
    // Trust nothing, not even ourselves: the package must pass the full validator before it is
    // written, so an invalid package never reaches the disk.
    const format::Package package = format::Package::from_bytes(bytes, options->output);
    format::validate_semantics(package);
    write_file_atomically(options->output, bytes);
    display.end("writing the package", std::chrono::duration<double>(std::chrono::steady_clock::now() - written).count());
    std::fputs(bake_summary(baked, package).c_str(), stdout);
    if (!options->report.empty()) {
      const std::string text = bake_report(baked, package).dump(2) + "\n";
      write_file_atomically(options->report, std::as_bytes(std::span(text.data(), text.size())));
    }
  });
}

}  // namespace nano::bake
