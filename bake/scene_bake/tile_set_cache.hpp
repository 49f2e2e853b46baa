#pragma once
// The tile-set stage kept on disk like the shells stage (shell_cache.hpp, docs/bake-estimate.md). The stage's whole work is tiles::make_membrane_tiles or
// make_soluble_cubes on a request that holds everything they read, so the key is the request's
// bytes (not its thread count: the set does not depend on it) and the value the WangSet, whose
// types index the request's own list: nothing to remap.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bake/scene_bake/shell_cache.hpp"
#include "bake/tiles/wang_set.hpp"
#include "bake/tiles/wang_sets.hpp"

namespace nano::scene_bake {

ShellStageKey tile_set_key(const tiles::MembraneTileRequest& request);
ShellStageKey tile_set_key(const tiles::SolubleCubeRequest& request);

std::vector<std::byte> encode_wang_set(const tiles::WangSet& set);
// The set the bytes hold when they decode whole into one of `types` molecule types; otherwise
// nullopt, and `why` says what is wrong.
std::optional<tiles::WangSet> decode_wang_set(std::span<const std::byte> bytes, std::size_t types, std::string& why);

// The file a key's set lives in: DIRECTORY/tiles-<key>.bin.
std::filesystem::path tile_set_cache_file(const std::filesystem::path& directory, const ShellStageKey& key);
// The key's set from `directory` (nullopt when there is none, or with a warning when it is unusable).
std::optional<tiles::WangSet> load_wang_set(const std::filesystem::path& directory, const ShellStageKey& key, std::size_t types);
void store_wang_set(const std::filesystem::path& directory, const ShellStageKey& key, const tiles::WangSet& set);

// The request's set: from the cache when it holds the request's, else made (and kept when there is
// a cache). `from_cache` says which.
tiles::WangSet cached_membrane_tiles(const tiles::MembraneTileRequest& request,
                                     const std::optional<std::filesystem::path>& cache, bool& from_cache);
tiles::WangSet cached_soluble_cubes(const tiles::SolubleCubeRequest& request,
                                    const std::optional<std::filesystem::path>& cache, bool& from_cache);

}  // namespace nano::scene_bake
