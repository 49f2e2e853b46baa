#pragma once
// Where per-user caches live: the XDG base directory for caches, as both binaries keep theirs there
// (nanoview's compiled pipelines, nanobake's shells stage).
#include <filesystem>
#include <optional>

namespace nano {

// The user's cache directory as the XDG base directory spec has it: $XDG_CACHE_HOME when it is an
// absolute path (a relative one is ignored, as the spec demands), else $HOME/.cache when HOME is
// absolute; nullopt when neither is usable (no cache is kept).
std::optional<std::filesystem::path> user_cache_directory();

}  // namespace nano
