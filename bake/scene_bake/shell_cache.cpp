#include "bake/scene_bake/shell_cache.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include <xxhash.h>

#include "bake/scene_bake/stage_bytes.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {

namespace {

constexpr char kMagic[8] = {'N', 'U', 'S', 'H', 'E', 'L', 'L', 'S'};
// magic, version, reserved, the key as 32 hex digits, payload size, XXH3-64 of the payload.
constexpr std::size_t kKeyAt = 16, kSizeAt = 48, kChecksumAt = 56, kHeaderBytes = 64;

XXH128_hash_t digest(std::span<const std::byte> material) { return XXH3_128bits(material.data(), material.size()); }

void put_pruning(StageWriter& w, const shell::PrunedMembrane& p) {
  w.put(std::uint64_t(p.dropped.size()));
  for (const std::vector<std::uint32_t>& keys : p.dropped) {
    w.put(std::uint64_t(keys.size()));
    w.put_all(keys);
  }
  w.put_all(p.dropped_by_type);
  w.put_all(p.alternates_by_type);
  for (const std::uint64_t v : {p.owned_copies, std::uint64_t(p.whole_surface), p.checked_triangles, p.checked_copies,
                                p.atom_pairs, p.copy_pairs_tested, p.clashing_pairs})
    w.put(v);
}

std::string get_pruning(StageReader& r, std::size_t triangles, std::size_t types, shell::PrunedMembrane& p) {
  std::uint64_t lists = 0;
  if (!r.get(lists) || lists != triangles) return "its dropped copies are not one list per triangle";
  p.dropped.resize(triangles);
  for (std::vector<std::uint32_t>& keys : p.dropped) {
    std::uint64_t n = 0;
    if (!r.get(n) || !r.get_all(keys, n)) return "it ends inside the dropped copies";
    for (std::size_t i = 1; i < keys.size(); ++i)
      if (!(keys[i - 1] < keys[i])) return "a triangle's dropped copies are not strictly ascending";
  }
  if (!r.get_all(p.dropped_by_type, types) || !r.get_all(p.alternates_by_type, types)) return "it ends inside the counts per type";
  std::uint64_t whole = 0;
  for (std::uint64_t* v : {&p.owned_copies, &whole, &p.checked_triangles, &p.checked_copies,
                           &p.atom_pairs, &p.copy_pairs_tested, &p.clashing_pairs})
    if (!r.get(*v)) return "it ends inside the pruning's counts";
  if (whole > 1) return "its whole-surface flag is neither 0 nor 1";
  p.whole_surface = whole == 1;
  return "";
}

// The stage's payload for a mesh of `triangles` and a set of `types`, or why it is not one.
std::string decode_payload(std::span<const std::byte> payload, std::size_t triangles, std::size_t types, ShellStage& s) {
  StageReader r(payload);
  std::uint64_t stored_triangles = 0, stored_types = 0;
  if (!r.get(stored_triangles) || !r.get(stored_types)) return "it ends before its sizes";
  if (stored_triangles != triangles || stored_types != types)
    return "it holds " + std::to_string(stored_triangles) + " triangles and " + std::to_string(stored_types) +
           " molecule types, the bake " + std::to_string(triangles) + " and " + std::to_string(types);
  if (!r.get_all(s.offsets, triangles) || !r.get_all(s.reach, triangles)) return "it ends inside the prisms";
  for (std::size_t t = 0; t < triangles; ++t) {
    const gpu::ShellOffsets& o = s.offsets[t];
    for (const float v : {o.h_plus, o.h_minus, o.side, s.reach[t]})
      if (!(std::isfinite(v) && v >= 0.f)) return "triangle " + std::to_string(t) + " has a negative or non-finite prism";
  }
  if (!r.get_all(s.owned_by_type, types) || !r.get_all(s.unfit_by_type, types)) return "it ends inside the copies per type";
  if (std::string wrong = get_pruning(r, triangles, types, s.pruning); !wrong.empty()) return wrong;
  if (!r.done()) return "bytes follow the stage";
  return "";
}

void warn(const std::filesystem::path& file, const std::string& what) {
  std::fprintf(stderr, "nanobake: warning: bake cache %s: %s\n", file.c_str(), what.c_str());
}

}  // namespace

ShellStageKey::ShellStageKey() { add(kShellCacheFormatVersion); }

void ShellStageKey::add_bytes(std::span<const std::byte> bytes) { material_.insert(material_.end(), bytes.begin(), bytes.end()); }

void ShellStageKey::add_text(const std::string& text) {
  add(std::uint64_t(text.size()));
  add_bytes(std::as_bytes(std::span<const char>(text)));
}

void ShellStageKey::add_types(const std::vector<tiles::MoleculeType>& types) {
  add(std::uint64_t(types.size()));
  for (const tiles::MoleculeType& t : types) {
    add_text(t.name);
    add_all(t.atoms);
    add(t.bounding_radius);
    add(t.up_axis);
  }
}

void ShellStageKey::add_instances(const std::vector<tiles::Instance>& instances) {
  add(std::uint64_t(instances.size()));
  for (const tiles::Instance& i : instances) {
    add(i.type);
    add(i.position);
    add(i.rotation);
    add(std::uint8_t(i.alternate));
    add(std::uint8_t(i.has_alternate));
  }
}

std::string ShellStageKey::hex() const {
  const XXH128_hash_t h = digest(material_);
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  return text;
}

std::uint64_t baker_build_hash() {
  static const std::uint64_t hash = [] {
    std::ifstream in("/proc/self/exe", std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    return in.bad() || bytes.empty() ? std::uint64_t{0} : std::uint64_t{XXH3_64bits(bytes.data(), bytes.size())};
  }();
  return hash;
}

std::filesystem::path shell_cache_file(const std::filesystem::path& directory, const ShellStageKey& key) {
  return directory / ("shells-" + key.hex() + ".bin");
}

std::vector<std::byte> wrap_cached_stage(std::string_view magic, const ShellStageKey& key, std::span<const std::byte> payload) {
  StageWriter file;
  for (std::size_t i = 0; i < sizeof kMagic; ++i) file.put(i < magic.size() ? magic[i] : ' ');
  file.put(kShellCacheFormatVersion);
  file.put(std::uint32_t{0});
  for (const char c : key.hex()) file.put(c);
  file.put(std::uint64_t(payload.size()));
  file.put(std::uint64_t(XXH3_64bits(payload.data(), payload.size())));
  file.bytes.insert(file.bytes.end(), payload.begin(), payload.end());
  return file.bytes;
}

std::vector<std::byte> encode_shell_stage(const ShellStageKey& key, const ShellStage& stage) {
  StageWriter payload;
  payload.put(std::uint64_t(stage.offsets.size()));
  payload.put(std::uint64_t(stage.owned_by_type.size()));
  payload.put_all(stage.offsets);
  payload.put_all(stage.reach);
  payload.put_all(stage.owned_by_type);
  payload.put_all(stage.unfit_by_type);
  put_pruning(payload, stage.pruning);
  return wrap_cached_stage(std::string_view(kMagic, sizeof kMagic), key, payload.bytes);
}

std::optional<std::span<const std::byte>> unwrap_cached_stage(std::span<const std::byte> bytes, std::string_view magic,
                                                              const ShellStageKey& key, std::string& why) {
  if (bytes.size() < kHeaderBytes) {
    why = "shorter than its header";
    return std::nullopt;
  }
  std::string stored(reinterpret_cast<const char*>(bytes.data()), sizeof kMagic);
  if (stored.substr(0, magic.size()) != magic) {
    why = "not a nanobake cache file of this stage";
    return std::nullopt;
  }
  std::uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 8, sizeof version);
  if (version != kShellCacheFormatVersion) {
    why = "format version " + std::to_string(version) + ", this baker reads " + std::to_string(kShellCacheFormatVersion);
    return std::nullopt;
  }
  const std::string expected = key.hex();
  if (std::memcmp(bytes.data() + kKeyAt, expected.data(), expected.size()) != 0) {
    why = "another stage's file (its key differs)";
    return std::nullopt;
  }
  std::uint64_t size = 0, checksum = 0;
  std::memcpy(&size, bytes.data() + kSizeAt, sizeof size);
  std::memcpy(&checksum, bytes.data() + kChecksumAt, sizeof checksum);
  const std::span<const std::byte> payload = bytes.subspan(kHeaderBytes);
  if (size != payload.size()) {
    why = "its header announces " + std::to_string(size) + " bytes of stage, the file holds " + std::to_string(payload.size());
    return std::nullopt;
  }
  if (XXH3_64bits(payload.data(), payload.size()) != checksum) {
    why = "its checksum does not match its bytes";
    return std::nullopt;
  }
  return payload;
}

std::optional<ShellStage> decode_shell_stage(std::span<const std::byte> bytes, const ShellStageKey& key,
                                             std::size_t triangles, std::size_t types, std::string& why) {
  const auto payload = unwrap_cached_stage(bytes, std::string_view(kMagic, sizeof kMagic), key, why);
  if (!payload) return std::nullopt;
  ShellStage stage;
  why = decode_payload(*payload, triangles, types, stage);
  if (!why.empty()) return std::nullopt;
  return stage;
}

std::optional<std::vector<std::byte>> read_cached_file(const std::filesystem::path& file) {
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(file, ignored)) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) {
    warn(file, "cannot be read; the stage is baked again");
    return std::nullopt;
  }
  const auto bytes = std::as_bytes(std::span<const char>(text));
  return std::vector<std::byte>(bytes.begin(), bytes.end());
}

void cached_file_used(const std::filesystem::path& file) {
  std::error_code ignored;
  std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ignored);
}

void cached_file_unusable(const std::filesystem::path& file, const std::string& why) {
  warn(file, why + "; the stage is baked again and the file replaced");
}

std::optional<ShellStage> load_shell_stage(const std::filesystem::path& directory, const ShellStageKey& key,
                                           std::size_t triangles, std::size_t types) {
  const std::filesystem::path file = shell_cache_file(directory, key);
  const std::optional<std::vector<std::byte>> bytes = read_cached_file(file);
  if (!bytes) return std::nullopt;
  std::string why;
  std::optional<ShellStage> stage = decode_shell_stage(*bytes, key, triangles, types, why);
  if (!stage) cached_file_unusable(file, why);
  else cached_file_used(file);
  return stage;
}

void trim_shell_cache(const std::filesystem::path& directory, std::uintmax_t budget, const std::filesystem::path& keep) {
  struct Entry {
    std::filesystem::path path;
    std::filesystem::file_time_type used;
    std::uintmax_t bytes;
  };
  std::vector<Entry> entries;
  std::uintmax_t total = 0;
  std::error_code error;
  for (const auto& e : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = e.path().filename().string();
    const bool stage_file = name.rfind("shells-", 0) == 0 || name.rfind("tiles-", 0) == 0;
    if (!e.is_regular_file(error) || !stage_file || e.path().extension() != ".bin") continue;
    const std::uintmax_t bytes = e.file_size(error);
    if (error) continue;
    entries.push_back({e.path(), e.last_write_time(error), bytes});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
  for (const Entry& e : entries) {
    if (total <= budget) break;
    if (e.path == keep) continue;
    if (std::filesystem::remove(e.path, error)) total -= e.bytes;
  }
}

void write_cached_file(const std::filesystem::path& directory, const std::filesystem::path& file,
                       const std::vector<std::byte>& bytes) {
  try {
    std::filesystem::create_directories(directory);
    write_file_atomically(file, bytes);
    trim_shell_cache(directory, kShellCacheBudgetBytes, file);
  } catch (const std::exception& e) {
    const auto* input_error = dynamic_cast<const InputError*>(&e);
    warn(file, std::string("cannot be saved (") + (input_error ? input_error->rule() : e.what()) + "); the next bake pays the stage again");
  }
}

void store_shell_stage(const std::filesystem::path& directory, const ShellStageKey& key, const ShellStage& stage) {
  write_cached_file(directory, shell_cache_file(directory, key), encode_shell_stage(key, stage));
}

}  // namespace nano::scene_bake
