#pragma once
// What a package was made from: baker version, the scene, every input file's hash, the seed.
// No timestamps and no absolute paths, so the same inputs and seed give byte-identical packages.
#include <cstdint>
#include <filesystem>
#include <string>

#include "bake/scene/scene_description.hpp"

namespace nano::scene_bake {

// XXH3-64 of a file's bytes as 16 hex digits; throws InputError naming an unreadable file.
std::string file_hash(const std::filesystem::path& path);

std::string provenance_json(const scene::SceneDescription& scene, std::uint64_t seed);

}  // namespace nano::scene_bake
