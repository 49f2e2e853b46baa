// `nanobake bake SCENE.json -o SCENE.nup` (also `nanobake SCENE.json -o ...`): the whole pipeline.
#include <chrono>
#include <cstdio>
#include <fstream>

#include "bake/cellpack/import_options.hpp"
#include "bake/cellpack/recipe_reader.hpp"
#include "bake/commands.hpp"
#include "bake/scene/scene_parser.hpp"
#include "bake/scene_bake/bake_estimate.hpp"
#include "bake/scene_bake/bake_progress.hpp"
#include "bake/scene_bake/bake_report.hpp"
#include "bake/scene_bake/scene_baker.hpp"
#include "common/atomic_file.hpp"
#include "common/user_cache_directory.hpp"
#include "common/error.hpp"
#include "common/json_document.hpp"
#include "format/validator.hpp"

namespace nano::bake {
// The command drives the pipeline of bake/scene_bake.
using namespace nano::scene_bake;

namespace {

struct SceneToBake {
  scene::SceneDescription scene;
  std::optional<cellpack::ImportResult> imported;  // the scene came from a cellPACK recipe
};

// The scene in `file`, or — for a cellPACK recipe — the scene it imports to, its paths relative to
// the recipe's folder, after printing the import's report.
SceneToBake scene_to_bake(const std::string& file, const cellpack::ImportArguments& recipe_arguments) {
  const Json document = read_json_file(file);
  if (!cellpack::is_cellpack_recipe(document)) {
    if (cellpack::any_import_option(recipe_arguments))
      throw InputError(file, "", "--structures, --server, --lipid-patch and --stand-ins are for cellPACK recipes; this is a scene");
    return {scene::parse_scene_description(document, file), std::nullopt};
  }
  const cellpack::ImportOptions import = cellpack::import_options(recipe_arguments, file, std::filesystem::path(file).parent_path());
  const cellpack::Recipe recipe = cellpack::parse_recipe(document, file, import.read);
  cellpack::ImportResult imported = cellpack::scene_from_recipe(recipe, import);
  std::fputs(cellpack::report_text(recipe, imported).c_str(), stdout);
  return {scene::parse_scene_description(imported.scene, file), std::move(imported)};
}

// What the bake placed, as the recipe check reads it: each compartment's copies, the medium's estimate.
cellpack::HeldCopies held_copies(const BakedScene& baked) {
  cellpack::HeldCopies held;
  for (const CompartmentSummary& c : baked.compartments)
    for (const auto& [molecule, copies] : c.copies) held[{c.name, molecule}] += static_cast<double>(copies);
  if (baked.medium)
    for (const MediumMoleculeCount& m : baked.medium->counts) held[{"medium", m.name}] += m.copies;
  return held;
}

// --cache-dir as given, else the user's cache directory's nanouniverse/bake; none with --no-cache or
// without a usable home (the bake then computes every stage, as it would with an empty cache).
std::optional<std::filesystem::path> bake_cache_directory(const std::string& given, bool no_cache) {
  if (no_cache) return std::nullopt;
  if (!given.empty()) return std::filesystem::absolute(given);
  if (const auto home = user_cache_directory()) return *home / "nanouniverse" / "bake";
  return std::nullopt;
}

void add_cache_options(CLI::App& cmd, std::string& cache_dir, bool& no_cache) {
  cmd.add_option("--cache-dir", cache_dir,
                 "where the shells stage is kept between bakes, under a fingerprint of its inputs (default: "
                 "$XDG_CACHE_HOME or ~/.cache, folder nanouniverse/bake)");
  cmd.add_flag("--no-cache", no_cache, "neither read nor keep the shells stage: every bake computes it")->excludes("--cache-dir");
}

// --max-memory as given, else what the machine has available (none when it cannot tell).
std::optional<double> memory_budget(const std::string& given) {
  if (!given.empty()) {
    const std::optional<double> bytes = parse_byte_size(given);
    if (!bytes) throw CLI::ValidationError("--max-memory", "expected a size such as 8G, 512M or 2000000000, got " + given);
    return bytes;
  }
  if (const double available = available_memory_bytes(); available > 0.0) return available;
  return std::nullopt;
}

}  // namespace

void add_bake_command(CLI::App& app) {
  struct Options {
    std::string scene, output, report;
    std::uint64_t seed = 0;
    int jobs = 2;
    std::string max_memory;
    bool dry_run = false, quiet = false, no_cache = false;
    std::string cache_dir;
    MeshCodec mesh_codec = MeshCodec::automatic;
    cellpack::ImportArguments recipe;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("bake", "Bake a scene description into a package (also: nanobake SCENE.json -o PKG)");
  cmd->add_option("scene", options->scene, "scene description (scene.json), or a cellPACK recipe imported on the way")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", options->output, "package to write (.nup)")->required();
  CLI::Option* seed = cmd->add_option("--seed", options->seed, "overrides the scene's seed");
  cmd->add_option("--jobs", options->jobs, "worker threads")->check(CLI::Range(1, 256));
  cmd->add_option("--report", options->report, "write a JSON report of what was baked");
  cmd->add_flag("--dry-run", options->dry_run,
                "check the scene and print the estimated time, peak memory and copy counts, without baking");
  cmd->add_option("--max-memory", options->max_memory,
                  "refuse a bake whose estimated peak memory passes this (e.g. 8G, 512M; default: what the machine has available)");
  cmd->add_flag("-q,--quiet", options->quiet, "print no progress");
  add_cache_options(*cmd, options->cache_dir, options->no_cache);
  cmd->add_option("--mesh-codec", options->mesh_codec,
                  "mesh sections: auto (Draco where smaller than zstd, meshes on Draco's exact grids), draco, or zstd "
                  "(meshes exactly as read)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, MeshCodec>{
          {"auto", MeshCodec::automatic}, {"draco", MeshCodec::draco}, {"zstd", MeshCodec::zstd}}));
  cellpack::add_import_options(*cmd, options->recipe, false, "cellPACK recipes (docs/scenes.md)");
  cmd->callback([options, seed] {
    remove_temporaries_on_interrupt();
    const SceneToBake to_bake = scene_to_bake(options->scene, options->recipe);
    const scene::SceneDescription& scene = to_bake.scene;
    BakeOptions bake_options;
    if (seed->count() > 0) bake_options.seed = options->seed;
    bake_options.jobs = options->jobs;
    bake_options.mesh_codec = options->mesh_codec;
    bake_options.estimate_only = options->dry_run;
    bake_options.cache_directory = bake_cache_directory(options->cache_dir, options->no_cache);
    bake_options.max_memory = memory_budget(options->max_memory);
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
    for (const std::string& warning : baked.warnings)
      std::fprintf(stderr, "nanobake: warning: %s: %s\n", options->scene.c_str(), warning.c_str());
    const cellpack::HeldCopies held = held_copies(baked);
    if (to_bake.imported) {
      int off = 0;
      std::fputs(cellpack::copy_number_check(*to_bake.imported, held, off).c_str(), stdout);
    }
    if (!options->report.empty()) {
      nlohmann::ordered_json report = bake_report(baked, package);
      if (to_bake.imported) report["cellpack_recipe"] = cellpack::report_json(*to_bake.imported, &held);
      const std::string text = report.dump(2) + "\n";
      write_file_atomically(options->report, std::as_bytes(std::span(text.data(), text.size())));
    }
  });
}

}  // namespace nano::bake
