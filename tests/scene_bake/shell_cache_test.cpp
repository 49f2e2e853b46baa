// The bake cache's shells files: a stage comes back exactly as it went in, and a file that is not
// this key's whole stage for this mesh and set (truncated, altered, another key, another shape,
// hostile counts) is refused with a reason instead of being trusted.
#include "bake/scene_bake/shell_cache.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

namespace nano::scene_bake {
namespace {

ShellStageKey key_of(int n) {
  ShellStageKey key;
  key.add(n);
  return key;
}

ShellStage sample_stage() {
  ShellStage s;
  s.offsets = {{1.f, 2.f, 3.f}, {0.f, 0.5f, 0.25f}, {4.f, 4.f, 4.f}};
  s.reach = {10.f, 0.f, 7.5f};
  s.owned_by_type = {100, 5};
  s.unfit_by_type = {0, 2};
  s.pruning.dropped = {{1, 5, 70000}, {}, {3}};
  s.pruning.dropped_by_type = {3, 1};
  s.pruning.alternates_by_type = {2, 0};
  s.pruning.owned_copies = 105;
  s.pruning.whole_surface = true;
  s.pruning.checked_triangles = 3;
  s.pruning.checked_copies = 105;
  s.pruning.atom_pairs = 40;
  s.pruning.copy_pairs_tested = 7;
  s.pruning.clashing_pairs = 4;
  return s;
}

std::optional<ShellStage> decode(const std::vector<std::byte>& bytes, const ShellStageKey& key, std::string& why) {
  return decode_shell_stage(bytes, key, 3, 2, why);
}

TEST(ShellCache, RoundTripKeepsEveryField) {
  const ShellStage in = sample_stage();
  std::string why;
  const std::optional<ShellStage> out = decode(encode_shell_stage(key_of(1), in), key_of(1), why);
  ASSERT_TRUE(out) << why;
  ASSERT_EQ(out->offsets.size(), 3u);
  for (std::size_t t = 0; t < 3; ++t) {
    EXPECT_EQ(out->offsets[t].h_plus, in.offsets[t].h_plus);
    EXPECT_EQ(out->offsets[t].h_minus, in.offsets[t].h_minus);
    EXPECT_EQ(out->offsets[t].side, in.offsets[t].side);
  }
  EXPECT_EQ(out->reach, in.reach);
  EXPECT_EQ(out->owned_by_type, in.owned_by_type);
  EXPECT_EQ(out->unfit_by_type, in.unfit_by_type);
  EXPECT_EQ(out->pruning.dropped, in.pruning.dropped);
  EXPECT_EQ(out->pruning.dropped_by_type, in.pruning.dropped_by_type);
  EXPECT_EQ(out->pruning.alternates_by_type, in.pruning.alternates_by_type);
  EXPECT_EQ(out->pruning.owned_copies, 105u);
  EXPECT_TRUE(out->pruning.whole_surface);
  EXPECT_EQ(out->pruning.checked_triangles, 3u);
  EXPECT_EQ(out->pruning.checked_copies, 105u);
  EXPECT_EQ(out->pruning.atom_pairs, 40u);
  EXPECT_EQ(out->pruning.copy_pairs_tested, 7u);
  EXPECT_EQ(out->pruning.clashing_pairs, 4u);
}

TEST(ShellCache, KeysDifferWithTheirBytes) {
  ShellStageKey a, b, c;
  a.add(1.0);
  b.add(1.0);
  c.add(std::nextafter(1.0, 2.0));
  EXPECT_EQ(a.hex(), b.hex());
  EXPECT_NE(a.hex(), c.hex());
  EXPECT_EQ(a.hex().size(), 32u);
  // A length prefix keeps ("ab", "c") apart from ("a", "bc").
  ShellStageKey d, e;
  d.add_text("ab"), d.add_text("c");
  e.add_text("a"), e.add_text("bc");
  EXPECT_NE(d.hex(), e.hex());
}

// Types and instances: equal lists give equal keys; each field the stage reads changes it.
TEST(ShellCache, KeysReadEveryFieldOfTypesAndInstances) {
  const auto key_of = [](const std::vector<nano::tiles::MoleculeType>& types, const std::vector<nano::tiles::Instance>& instances) {
    ShellStageKey k;
    k.add_types(types);
    k.add_instances(instances);
    return k.hex();
  };
  nano::tiles::MoleculeType type{"POPC", {{{0.f, 0.f, 1.f}, 1.7f}}, 2.7f, {0.f, 0.f, 1.f}};
  nano::tiles::Instance instance{0, {1.f, 2.f, 3.f}, glm::quat(1.f, 0.f, 0.f, 0.f)};
  const std::string base = key_of({type}, {instance});
  EXPECT_EQ(base, key_of({type}, {instance}));
  std::vector<std::string> changed;
  auto t = type;
  t.name = "POPE", changed.push_back(key_of({t}, {instance}));
  t = type, t.atoms[0].radius = 1.8f, changed.push_back(key_of({t}, {instance}));
  t = type, t.bounding_radius = 2.8f, changed.push_back(key_of({t}, {instance}));
  t = type, t.up_axis = {0.f, 1.f, 0.f}, changed.push_back(key_of({t}, {instance}));
  auto i = instance;
  i.type = 1, changed.push_back(key_of({type}, {i}));
  i = instance, i.position.z = 4.f, changed.push_back(key_of({type}, {i}));
  i = instance, i.rotation = glm::quat(0.f, 1.f, 0.f, 0.f), changed.push_back(key_of({type}, {i}));
  i = instance, i.alternate = true, changed.push_back(key_of({type}, {i}));
  i = instance, i.has_alternate = true, changed.push_back(key_of({type}, {i}));
  changed.push_back(key_of({type}, {instance, instance}));
  for (std::size_t k = 0; k < changed.size(); ++k) EXPECT_NE(changed[k], base) << "change " << k;
}

TEST(ShellCache, EveryTruncationIsRefused) {
  const std::vector<std::byte> whole = encode_shell_stage(key_of(1), sample_stage());
  for (std::size_t n = 0; n < whole.size(); ++n) {
    std::string why;
    EXPECT_FALSE(decode(std::vector<std::byte>(whole.begin(), whole.begin() + n), key_of(1), why)) << n;
    EXPECT_FALSE(why.empty()) << n;
  }
}

TEST(ShellCache, EveryAlteredByteIsRefused) {
  // Each byte flipped: the checksum, the magic, the version or the key refuses it (no flip may
  // decode to another stage).
  const std::vector<std::byte> whole = encode_shell_stage(key_of(1), sample_stage());
  for (std::size_t i = 0; i < whole.size(); ++i) {
    std::vector<std::byte> bytes = whole;
    bytes[i] ^= std::byte{0x40};
    std::string why;
    if (i >= 12 && i < 16) continue;  // the reserved word is not read
    EXPECT_FALSE(decode(bytes, key_of(1), why)) << "byte " << i;
  }
}

TEST(ShellCache, AnotherKeyOrShapeIsRefused) {
  const std::vector<std::byte> bytes = encode_shell_stage(key_of(1), sample_stage());
  std::string why;
  EXPECT_FALSE(decode(bytes, key_of(2), why));
  EXPECT_NE(why.find("key"), std::string::npos) << why;
  EXPECT_FALSE(decode_shell_stage(bytes, key_of(1), 4, 2, why));
  EXPECT_NE(why.find("3 triangles"), std::string::npos) << why;
  EXPECT_FALSE(decode_shell_stage(bytes, key_of(1), 3, 5, why));
}

TEST(ShellCache, InconsistentStagesAreRefusedEvenWithAValidChecksum) {
  // Written by a broken or hostile writer: the checksum matches, the content does not make sense.
  ShellStage descending = sample_stage();
  descending.pruning.dropped[0] = {5, 1};
  std::string why;
  EXPECT_FALSE(decode(encode_shell_stage(key_of(1), descending), key_of(1), why));
  EXPECT_NE(why.find("ascending"), std::string::npos) << why;
  ShellStage negative = sample_stage();
  negative.offsets[1].side = -1.f;
  EXPECT_FALSE(decode(encode_shell_stage(key_of(1), negative), key_of(1), why));
  ShellStage not_a_number = sample_stage();
  not_a_number.reach[2] = std::nanf("");
  EXPECT_FALSE(decode(encode_shell_stage(key_of(1), not_a_number), key_of(1), why));
  ShellStage lists = sample_stage();
  lists.pruning.dropped.pop_back();
  EXPECT_FALSE(decode(encode_shell_stage(key_of(1), lists), key_of(1), why));
}

TEST(ShellCache, StoreThenLoadAndAGarbageFileIsIgnored) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "nano_shell_cache_test";
  std::filesystem::remove_all(dir);
  EXPECT_FALSE(load_shell_stage(dir, key_of(7), 3, 2));  // no directory yet: a miss, no warning
  store_shell_stage(dir, key_of(7), sample_stage());
  ASSERT_TRUE(std::filesystem::exists(shell_cache_file(dir, key_of(7))));
  const std::optional<ShellStage> loaded = load_shell_stage(dir, key_of(7), 3, 2);
  ASSERT_TRUE(loaded);
  EXPECT_EQ(loaded->pruning.dropped, sample_stage().pruning.dropped);
  {
    std::ofstream garbage(shell_cache_file(dir, key_of(7)), std::ios::binary | std::ios::trunc);
    garbage << "not a cache file at all, but long enough to hold a header's worth of bytes......";
  }
  EXPECT_FALSE(load_shell_stage(dir, key_of(7), 3, 2));
  std::filesystem::remove_all(dir);
}

TEST(ShellCache, TrimmingKeepsTheMostRecentlyUsedWithinTheBudget) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "nano_shell_cache_trim_test";
  std::filesystem::remove_all(dir);
  for (int k = 0; k < 4; ++k) store_shell_stage(dir, key_of(k), sample_stage());
  const std::uintmax_t one = std::filesystem::file_size(shell_cache_file(dir, key_of(0)));
  // Oldest first: 0, 1, 2, 3; then 1 is used (a hit touches it).
  const auto now = std::filesystem::file_time_type::clock::now();
  for (int k = 0; k < 4; ++k)
    std::filesystem::last_write_time(shell_cache_file(dir, key_of(k)), now - std::chrono::hours(10 - k));
  ASSERT_TRUE(load_shell_stage(dir, key_of(1), 3, 2));
  std::ofstream(dir / "notes.txt") << "not the cache's";
  trim_shell_cache(dir, 2 * one, shell_cache_file(dir, key_of(0)));
  EXPECT_TRUE(std::filesystem::exists(shell_cache_file(dir, key_of(0))));  // kept: the one just written
  EXPECT_TRUE(std::filesystem::exists(shell_cache_file(dir, key_of(1))));  // the most recently used
  EXPECT_FALSE(std::filesystem::exists(shell_cache_file(dir, key_of(2))));
  EXPECT_FALSE(std::filesystem::exists(shell_cache_file(dir, key_of(3))));
  EXPECT_TRUE(std::filesystem::exists(dir / "notes.txt"));  // only its own files are trimmed
  std::filesystem::remove_all(dir);
}

TEST(ShellCache, TheBuildHashIsStable) {
  EXPECT_NE(baker_build_hash(), 0u);
  EXPECT_EQ(baker_build_hash(), baker_build_hash());
}

}  // namespace
}  // namespace nano::scene_bake
