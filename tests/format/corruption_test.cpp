// A corruption corpus generated here from a valid package: every case must be rejected, and for
// the right reason.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <zstd.h>

#include "format/layout.hpp"
#include "tests/format/package_bytes.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::format::test {
namespace {

class Corruption : public ::testing::Test {
protected:
  void SetUp() override {
    scene_ = make_sample_scene();
    good_ = build(scene_, Compression::zstd_if_smaller);
    ASSERT_EQ(broken_rule(good_), std::nullopt);
  }
  std::size_t entry(SectionKind k) const { return entry_at(entry_index(good_, k)); }
  std::uint64_t field(std::size_t at, int width) const { return get_le(good_, at, width); }

  SampleScene scene_;
  std::vector<std::byte> good_;
};

using Rules = std::set<Rule>;

void expect_rule(std::span<const std::byte> bytes, const Rules& allowed, const std::string& what) {
  const std::optional<Rule> r = broken_rule(bytes);
  ASSERT_TRUE(r.has_value()) << what << ": accepted";
  EXPECT_TRUE(allowed.count(*r)) << what << ": rejected as " << rule_name(*r);
}

// Exhaustive rather than random: every byte of a mostly-zstd and of an all-raw package.
TEST_F(Corruption, EverySingleByteFlipIsDetected) {
  std::mt19937 rng(7);
  for (const std::vector<std::byte>& pkg : {good_, build(scene_, Compression::none)}) {
    ASSERT_EQ(broken_rule(pkg), std::nullopt);
    for (std::size_t i = 0; i < pkg.size(); ++i) {
      auto bad = pkg;
      bad[i] ^= std::byte(1 + rng() % 255);
      ASSERT_NE(broken_rule(bad), std::nullopt) << "flip at byte " << i << " of " << pkg.size() << " went unnoticed";
    }
  }
}

TEST_F(Corruption, TruncationAtSectionBoundariesAndRandomOffsets) {
  std::vector<std::size_t> cuts = {0, 1, 63, 64, 65};
  const std::size_t count = field(32, 4);
  cuts.push_back(entry_at(count));
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t off = get_le(good_, entry_at(i) + 8, 8), size = get_le(good_, entry_at(i) + 16, 8);
    for (std::uint64_t c : {off - 1, off, off + 1, off + size - 1, off + size}) cuts.push_back(c);
  }
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) cuts.push_back(rng() % good_.size());
  for (std::size_t cut : cuts) {
    if (cut >= good_.size()) continue;
    expect_rule(std::span(good_).first(cut), {Rule::truncated, Rule::file_size_mismatch}, "cut at " + std::to_string(cut));
  }
  // Appended bytes count too.
  auto longer = good_;
  longer.push_back(std::byte{0});
  expect_rule(longer, {Rule::file_size_mismatch}, "one byte appended");
}

TEST_F(Corruption, EveryHeaderFieldPerturbed) {
  auto bad_magic = good_;
  bad_magic[3] = std::byte{'X'};
  expect_rule(bad_magic, {Rule::bad_magic}, "magic");
  for (const Field& f : kHeaderFields) {
    for (bool reseal : {false, true}) {
      auto bad = good_;
      put_le(bad, f.offset, f.width, get_le(bad, f.offset, f.width) + 1);
      if (reseal && std::string(f.name) != "checksum") seal_header(bad);
      const std::string what = std::string(f.name) + (reseal ? " (resealed)" : "");
      const std::string name = f.name;
      if (name == "version_major") expect_rule(bad, {Rule::unsupported_version}, what);
      else if (name == "endian_mark") expect_rule(bad, {Rule::bad_endianness}, what);
      else if (name == "file_size") expect_rule(bad, {Rule::file_size_mismatch}, what);
      else if (name == "version_minor" && reseal) EXPECT_EQ(broken_rule(bad), std::nullopt) << "a newer minor must be read";
      else if ((name == "table_offset" || name == "section_count") && reseal)
        EXPECT_NE(broken_rule(bad), std::nullopt) << what << ": a table read from the wrong place was accepted";
      else if (!reseal || name == "checksum") expect_rule(bad, {Rule::header_checksum}, what);
      else expect_rule(bad, {Rule::nonzero_reserved}, what);
    }
  }
}

TEST_F(Corruption, EveryTableFieldPerturbed) {
  for (SectionKind k : {SectionKind::strings, SectionKind::occupancy}) {  // stored raw / stored zstd
    const bool zstd = get_le(good_, entry(k) + 4, 2) == 1;
    ASSERT_EQ(zstd, k == SectionKind::occupancy);
    for (const Field& f : kEntryFields) {
      const std::string what = section_kind_name(k) + "." + f.name;
      auto unsealed = good_;
      put_le(unsealed, entry(k) + f.offset, f.width, get_le(unsealed, entry(k) + f.offset, f.width) ^ 0x10);
      expect_rule(unsealed, {Rule::header_checksum}, what + " without resealing");
      auto bad = unsealed;
      seal_header(bad);
      const std::string name = f.name;
      if (name == "kind") expect_rule(bad, {Rule::duplicate_section}, what);  // ^0x10: 1 <-> 17, both present
      else if (name == "codec") expect_rule(bad, {Rule::unknown_codec}, what);
      else if (name == "flags") expect_rule(bad, {Rule::nonzero_reserved}, what);
      else if (name == "offset") expect_rule(bad, {Rule::misaligned}, what);
      else if (name == "stored_size") expect_rule(bad, {Rule::overlap, Rule::nonzero_padding, Rule::stored_checksum, Rule::section_bounds}, what);
      else if (name == "raw_size") expect_rule(bad, {zstd ? Rule::decompression : Rule::record_size}, what);
      else if (name == "stored_checksum") expect_rule(bad, {Rule::stored_checksum}, what);
      else if (name == "raw_checksum") expect_rule(bad, {zstd ? Rule::raw_checksum : Rule::nonzero_reserved}, what);
    }
  }
}

TEST_F(Corruption, OverlappingSections) {
  auto bad = good_;
  put_le(bad, entry(SectionKind::atoms) + 8, 8, field(entry(SectionKind::molecules) + 8, 8));
  seal_header(bad);
  expect_rule(bad, {Rule::overlap}, "atoms over molecules");
}

TEST_F(Corruption, SectionsOutsideTheFileOrOverTheTable) {
  const std::size_t e = entry(SectionKind::provenance);
  const std::uint64_t beyond = align_up(good_.size() + 1, 256);
  for (auto [off, size] : {std::pair<std::uint64_t, std::uint64_t>{beyond, 16},
                           {field(e + 8, 8), std::uint64_t{1} << 63},
                           {std::uint64_t{1} << 63, 16},
                           {~std::uint64_t{255}, 512},  // offset + size wraps around
                           {0, 16}}) {                  // over the header
    auto bad = good_;
    put_le(bad, e + 8, 8, off);
    put_le(bad, e + 16, 8, size);
    seal_header(bad);
    expect_rule(bad, {Rule::section_bounds}, "offset " + std::to_string(off) + " size " + std::to_string(size));
  }
}

TEST_F(Corruption, MisalignedOffset) {
  for (std::uint64_t delta : {1, 4, 16, 128}) {
    auto bad = good_;
    put_le(bad, entry(SectionKind::atoms) + 8, 8, field(entry(SectionKind::atoms) + 8, 8) + delta);
    seal_header(bad);
    expect_rule(bad, {Rule::misaligned}, "offset + " + std::to_string(delta));
  }
}

TEST_F(Corruption, NonZeroPadding) {
  const std::size_t count = field(32, 4);
  int gaps = 0;
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const std::uint64_t end = field(entry_at(i) + 8, 8) + field(entry_at(i) + 16, 8);
    const std::uint64_t next = field(entry_at(i + 1) + 8, 8);
    for (std::uint64_t at : {end, next - 1}) {
      if (at < end || at >= next) continue;
      auto bad = good_;
      bad[at] = std::byte{0x80};
      expect_rule(bad, {Rule::nonzero_padding}, "padding byte " + std::to_string(at));
      ++gaps;
    }
  }
  EXPECT_GT(gaps, 10);
}

TEST_F(Corruption, AbsurdCounts) {
  auto many = good_;
  put_le(many, 32, 4, 0xffffffffu);  // no table that long exists to reseal: the count is checked first
  expect_rule(many, {Rule::table_bounds}, "2^32-1 sections");
  auto far = good_;
  put_le(far, 24, 8, std::uint64_t{1} << 63);
  expect_rule(far, {Rule::table_bounds}, "table at 2^63");
  for (SectionKind k : {SectionKind::occupancy, SectionKind::strings}) {  // zstd / raw
    auto huge = good_;
    put_le(huge, entry(k) + 24, 8, std::uint64_t{1} << 63);
    seal_header(huge);
    expect_rule(huge, {k == SectionKind::occupancy ? Rule::raw_size_limit : Rule::record_size}, "raw size 2^63");
  }
}

TEST_F(Corruption, ClaimedRawSizeOfOneTerabyteIsRefusedBeforeAllocating) {
  auto bad = good_;
  put_le(bad, entry(SectionKind::occupancy) + 24, 8, std::uint64_t{1} << 40);
  seal_header(bad);
  expect_rule(bad, {Rule::raw_size_limit}, "1 TiB claim");
}

TEST_F(Corruption, WrongRawSize) {
  auto bad = good_;
  put_le(bad, entry(SectionKind::occupancy) + 24, 8, scene_.occupancy.size() - 1);
  seal_header(bad);
  expect_rule(bad, {Rule::decompression}, "raw size one short");
}

TEST_F(Corruption, UnknownCodecAndEndianness) {
  auto bad = good_;
  put_le(bad, entry(SectionKind::atoms) + 4, 2, 7);
  seal_header(bad);
  expect_rule(bad, {Rule::unknown_codec}, "codec 7");
  auto big = good_;
  put_le(big, 12, 4, 0x04030201);  // what a big-endian writer would produce
  seal_header(big);
  try {
    (void)Package::from_bytes(big, "big.nup");
    FAIL() << "big-endian package accepted";
  } catch (const PackageError& e) {
    EXPECT_EQ(e.code(), Rule::bad_endianness);
    EXPECT_NE(std::string(e.what()).find("big-endian"), std::string::npos);
  }
}

TEST_F(Corruption, EmptyAndTinyFiles) {
  try {
    (void)Package::from_bytes({}, "empty.nup");
    FAIL();
  } catch (const PackageError& e) {
    EXPECT_EQ(e.code(), Rule::truncated);
    EXPECT_NE(std::string(e.what()).find("empty file"), std::string::npos);
  }
  expect_rule(std::span(good_).first(10), {Rule::truncated}, "10 bytes");
}

}  // namespace
}  // namespace nano::format::test
