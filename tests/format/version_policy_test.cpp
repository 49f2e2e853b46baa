// What this reader does with other versions and with section kinds it does not know.
#include <gtest/gtest.h>

#include "tests/format/package_bytes.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::format::test {
namespace {

std::vector<std::byte> with_version(std::uint16_t major, std::uint16_t minor) {
  std::vector<std::byte> b = build(make_sample_scene());
  put_le(b, 8, 2, major);
  put_le(b, 10, 2, minor);
  seal_header(b);
  return b;
}

TEST(VersionPolicy, NewerMinorIsRead) {
  const Package p = Package::from_bytes(with_version(kVersionMajor, kVersionMinor + 3));
  EXPECT_EQ(p.header().version_minor, kVersionMinor + 3);
  EXPECT_NO_THROW(validate_semantics(p));
}

TEST(VersionPolicy, OtherMajorIsRefusedNamingBothVersions) {
  for (std::uint16_t major : {std::uint16_t{0}, std::uint16_t{1}, std::uint16_t{3}, std::uint16_t{0xffff}}) {
    try {
      (void)Package::from_bytes(with_version(major, 7), "v.nup");
      ADD_FAILURE() << "major " << major << " accepted";
    } catch (const PackageError& e) {
      EXPECT_EQ(e.code(), Rule::unsupported_version);
      const std::string msg = e.what();
      EXPECT_NE(msg.find("version " + std::to_string(major) + ".7 found"), std::string::npos) << msg;
      EXPECT_NE(msg.find("supports major version 2"), std::string::npos) << msg;
    }
  }
}

std::vector<std::byte> with_unknown_section(std::uint16_t flags) {
  static const SampleScene s = make_sample_scene();
  static const std::vector<std::byte> future(100, std::byte{0x42});
  std::vector<SectionSource> sections = sections_of(s, Compression::none);
  sections.insert(sections.begin() + 3, SectionSource{4711, future, Compression::zstd_if_smaller, flags});
  return build_package(sections);
}

TEST(VersionPolicy, UnknownOptionalSectionIsSkippedButVerified) {
  const std::vector<std::byte> b = with_unknown_section(0);
  const Package p = Package::from_bytes(b);
  EXPECT_NO_THROW(validate_semantics(p));
  ASSERT_EQ(p.entries().size(), sections_of(make_sample_scene(), Compression::none).size() + 1);
  EXPECT_EQ(p.entries()[3].kind, 4711u);
  EXPECT_EQ(p.entries()[3].codec, static_cast<std::uint16_t>(Codec::zstd));
  // Its bytes are still covered by the checksum.
  auto bad = b;
  bad[p.entries()[3].offset] ^= std::byte{1};
  EXPECT_EQ(broken_rule(bad), Rule::stored_checksum);
}

TEST(VersionPolicy, UnknownRequiredSectionIsRefused) {
  EXPECT_EQ(broken_rule(with_unknown_section(kSectionRequired)), Rule::unknown_required_section);
}

TEST(PackageError, MessageNamesFileSectionOffsetAndRule) {
  const PackageError e("x.nup", Rule::index_out_of_range, Location{2, 1234, false}, "molecules[1]: bad");
  EXPECT_STREQ(e.what(), "x.nup:section molecules, byte 1234: index-out-of-range: molecules[1]: bad");
  EXPECT_EQ(e.code(), Rule::index_out_of_range);
  EXPECT_EQ(e.file(), "x.nup");
  EXPECT_EQ(describe(Location{std::nullopt, 16, false}), "byte 16");
  EXPECT_EQ(describe(Location{17, 300, true}), "section occupancy, decompressed byte 300");
  EXPECT_STREQ(rule_name(Rule::stored_checksum), "stored-checksum");
}

}  // namespace
}  // namespace nano::format::test
