#pragma once
// The shells stage of one compartment (its prisms and the clash pruning of its membrane: minutes for
// a red cell) kept on disk under a fingerprint of everything the stage reads: the mesh, the Wang
// set's tiles and molecule types, the recipe, the surface checks, the per-compartment counts and
// the baker's own executable. A scene baked again with other placements, another medium or another
// camera, or another scene wearing the same membrane on the same mesh with the same seed, takes the
// stage from the file instead. A cache file is read like any input: one that does not decode to a
// result of the right shape for this mesh and set is ignored (with a warning) and replaced.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bake/shell/membrane_pruning.hpp"
#include "bake/tiles/molecule_type.hpp"
#include "shared/shell_prism.h"

namespace nano::scene_bake {

inline constexpr std::uint32_t kShellCacheFormatVersion = 1;

// What the shells and the pruning give a compartment's membrane, indexed by triangle or by the
// Wang set's molecule type (never by library molecule: another scene lays its library out otherwise).
struct ShellStage {
  std::vector<gpu::ShellOffsets> offsets;  // per triangle
  std::vector<float> reach;                // per triangle
  std::vector<std::uint64_t> owned_by_type;  // copies the triangles own, per type
  std::vector<std::uint64_t> unfit_by_type;  // proteins no prism held, per type
  shell::PrunedMembrane pruning;             // with every dropped copy's key
};

// A 128-bit fingerprint built from the bytes of the stage's inputs, in order.
class ShellStageKey {
public:
  ShellStageKey();
  void add_bytes(std::span<const std::byte> bytes);
  template <typename T>
  void add(const T& value) {
    add_bytes(std::as_bytes(std::span<const T, 1>(&value, 1)));
  }
  template <typename T>
  void add_all(const std::vector<T>& values) {
    add(std::uint64_t(values.size()));
    add_bytes(std::as_bytes(std::span<const T>(values)));
  }
  void add_text(const std::string& text);
  // Molecule types (name, atoms, radius, up axis) and tile instances (type, pose, alternate flags),
  // each list led by its length: what the shells' and the tile sets' keys both read.
  void add_types(const std::vector<tiles::MoleculeType>& types);
  void add_instances(const std::vector<tiles::Instance>& instances);
  std::string hex() const;  // 32 hex digits

private:
  std::vector<std::byte> material_;
};

// XXH3-64 of the running executable's bytes (/proc/self/exe): any rebuild of the baker is another
// stage. Computed once per process; 0 when the file cannot be read (then nothing is cached).
std::uint64_t baker_build_hash();

// The file a key's stage lives in: DIRECTORY/shells-<key>.bin.
std::filesystem::path shell_cache_file(const std::filesystem::path& directory, const ShellStageKey& key);

std::vector<std::byte> encode_shell_stage(const ShellStageKey& key, const ShellStage& stage);
// The stage a file holds when it is whole (magic, version, checksum), is this key's and fits a mesh
// of `triangles` triangles and a set of `types` types; otherwise nullopt and `why` says what is wrong.
std::optional<ShellStage> decode_shell_stage(std::span<const std::byte> bytes, const ShellStageKey& key,
                                             std::size_t triangles, std::size_t types, std::string& why);

// Reads the key's file from `directory`: nullopt when there is none, or (with a warning on stderr
// naming the file) when it is unusable.
std::optional<ShellStage> load_shell_stage(const std::filesystem::path& directory, const ShellStageKey& key,
                                           std::size_t triangles, std::size_t types);
// Writes it atomically; a failure is a warning on stderr, never an error: the cache only saves time.
// Then the directory's oldest shells files (by last use: a hit touches its file) go until the rest
// fit kShellCacheBudgetBytes, this one kept: every rebuild of the baker leaves its files unused.
void store_shell_stage(const std::filesystem::path& directory, const ShellStageKey& key, const ShellStage& stage);

// The file around any cached stage (shells, tile sets): an 8-byte magic naming the stage, the
// format version, the key, the payload's size and checksum, the payload.
std::vector<std::byte> wrap_cached_stage(std::string_view magic, const ShellStageKey& key, std::span<const std::byte> payload);
// The payload when the bytes are a whole file of this stage and key; otherwise nullopt, `why` set.
std::optional<std::span<const std::byte>> unwrap_cached_stage(std::span<const std::byte> bytes, std::string_view magic,
                                                              const ShellStageKey& key, std::string& why);
// A cache file's bytes: nullopt when there is none, or (with a warning naming it) when it cannot be read.
std::optional<std::vector<std::byte>> read_cached_file(const std::filesystem::path& file);
void cached_file_used(const std::filesystem::path& file);  // a hit: the file is recently used
void cached_file_unusable(const std::filesystem::path& file, const std::string& why);  // the warning
// Writes atomically, then trims the directory's stage files to kShellCacheBudgetBytes, this one
// kept; a failure is a warning on stderr, never an error: the cache only saves time.
void write_cached_file(const std::filesystem::path& directory, const std::filesystem::path& file,
                       const std::vector<std::byte>& bytes);

inline constexpr std::uintmax_t kShellCacheBudgetBytes = std::uintmax_t{2} << 30;

// Removes the least recently used shells-*.bin files of `directory` beyond `budget` bytes, never `keep`.
void trim_shell_cache(const std::filesystem::path& directory, std::uintmax_t budget, const std::filesystem::path& keep);

}  // namespace nano::scene_bake
