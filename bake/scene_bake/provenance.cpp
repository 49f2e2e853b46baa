#include "bake/scene_bake/provenance.hpp"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include <nlohmann/json.hpp>
#include <xxhash.h>

#include "common/error.hpp"

#ifndef NANO_VERSION
#define NANO_VERSION "unknown"
#endif

namespace nano::scene_bake {
namespace {

std::string relative_to_scene(const std::filesystem::path& file, const scene::SceneDescription& scene) {
  return file.lexically_relative(scene.source.parent_path()).generic_string();
}

}  // namespace

std::string file_hash(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot read the file to hash it");
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    XXH3_64bits_update(state, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  const XXH64_hash_t hash = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

std::string provenance_json(const scene::SceneDescription& scene, std::uint64_t seed) {
  nlohmann::ordered_json j;
  j["baker"] = "nanobake";
  j["version"] = NANO_VERSION;
  j["scene"] = {{"file", scene.source.filename().string()}, {"xxh3", file_hash(scene.source)}};
  j["seed"] = seed;
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const scene::MoleculeDescription& m : scene.molecules) {
    if (!m.stand_in_spheres.empty())  // its spheres are in the scene file, hashed above
      inputs.push_back({{"molecule", m.name}, {"stand_in", m.stand_in_from}, {"spheres", m.stand_in_spheres.size()}});
    else
      inputs.push_back({{"molecule", m.name}, {"file", relative_to_scene(m.file, scene)}, {"xxh3", file_hash(m.file)}});
  }
  for (const scene::CompartmentDescription& c : scene.compartments)
    if (c.mesh.kind == scene::MeshSource::Kind::file)
      inputs.push_back({{"mesh", c.name}, {"file", relative_to_scene(c.mesh.file, scene)}, {"xxh3", file_hash(c.mesh.file)}});
  j["inputs"] = inputs;
  return j.dump(2);
}

}  // namespace nano::scene_bake
