// The header and table serialization against byte offsets written down in docs/format.md.
#include <gtest/gtest.h>

#include "format/checked_math.hpp"
#include "format/layout.hpp"
#include "tests/format/package_bytes.hpp"

namespace nano::format::test {
namespace {

std::vector<std::byte> bytes_of(std::size_t n) { return std::vector<std::byte>(n); }

TEST(Layout, HeaderFieldsAtDocumentedOffsets) {
  Header h;
  h.version_major = 0x0102;
  h.version_minor = 0x0304;
  h.endian_mark = kEndianMark;
  h.file_size = 0x1112131415161718;
  h.table_offset = 0x2122232425262728;
  h.section_count = 0x31323334;
  h.flags = 0x41424344;
  h.reserved0 = 0x5152535455565758;
  h.reserved1 = 0x6162636465666768;
  h.checksum = 0x7172737475767778;
  auto b = bytes_of(kHeaderSize);
  encode_header(h, std::span(b).first<kHeaderSize>());
  const unsigned char magic[8] = {0x89, 'N', 'U', 'P', '\r', '\n', 0x1a, '\n'};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(std::to_integer<unsigned char>(b[i]), magic[i]);
  const std::uint64_t expected[] = {0x0102, 0x0304, 0x01020304, 0x1112131415161718, 0x2122232425262728, 0x31323334,
                                    0x41424344, 0x5152535455565758, 0x6162636465666768, 0x7172737475767778};
  for (std::size_t i = 0; i < std::size(kHeaderFields); ++i)
    EXPECT_EQ(get_le(b, kHeaderFields[i].offset, kHeaderFields[i].width), expected[i]) << kHeaderFields[i].name;
  EXPECT_EQ(std::to_integer<unsigned>(b[12]), 0x04u);  // little-endian mark reads 04 03 02 01
  const Header back = decode_header(std::span<const std::byte>(b).first<kHeaderSize>());
  EXPECT_EQ(back.version_major, h.version_major);
  EXPECT_EQ(back.version_minor, h.version_minor);
  EXPECT_EQ(back.file_size, h.file_size);
  EXPECT_EQ(back.table_offset, h.table_offset);
  EXPECT_EQ(back.section_count, h.section_count);
  EXPECT_EQ(back.flags, h.flags);
  EXPECT_EQ(back.reserved0, h.reserved0);
  EXPECT_EQ(back.reserved1, h.reserved1);
  EXPECT_EQ(back.checksum, h.checksum);
}

TEST(Layout, EntryFieldsAtDocumentedOffsets) {
  const SectionEntry e{0x01020304, 0x1112, 0x2122, 0x3132333435363738, 0x4142434445464748, 0x5152535455565758,
                       0x6162636465666768, 0x7172737475767778};
  auto b = bytes_of(kEntrySize);
  encode_section_entry(e, std::span(b).first<kEntrySize>());
  const std::uint64_t expected[] = {e.kind, e.codec, e.flags, e.offset, e.stored_size, e.raw_size, e.stored_checksum, e.raw_checksum};
  for (std::size_t i = 0; i < std::size(kEntryFields); ++i)
    EXPECT_EQ(get_le(b, kEntryFields[i].offset, kEntryFields[i].width), expected[i]) << kEntryFields[i].name;
  const SectionEntry back = decode_section_entry(std::span<const std::byte>(b).first<kEntrySize>());
  EXPECT_EQ(back.kind, e.kind);
  EXPECT_EQ(back.codec, e.codec);
  EXPECT_EQ(back.flags, e.flags);
  EXPECT_EQ(back.offset, e.offset);
  EXPECT_EQ(back.stored_size, e.stored_size);
  EXPECT_EQ(back.raw_size, e.raw_size);
  EXPECT_EQ(back.stored_checksum, e.stored_checksum);
  EXPECT_EQ(back.raw_checksum, e.raw_checksum);
}

TEST(Layout, Xxh3KnownValues) {
  // Reference values of XXH3-64 (seed 0) from the xxHash test vectors.
  EXPECT_EQ(xxh3({}), 0x2D06800538D394C2ull);
  EXPECT_NE(xxh3(std::as_bytes(std::span("a", 1))), xxh3(std::as_bytes(std::span("b", 1))));
}

TEST(Layout, HeaderChecksumCoversHeaderPrefixAndTable) {
  auto b = bytes_of(kHeaderSize + kEntrySize);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::byte(i * 7);
  const auto header = std::span<const std::byte>(b).first<kHeaderSize>();
  const auto table = std::span<const std::byte>(b).subspan(kHeaderSize);
  // Oracle: XXH3 of the concatenation, computed in one piece.
  std::vector<std::byte> joined(b.begin(), b.begin() + 56);
  joined.insert(joined.end(), b.begin() + 64, b.end());
  EXPECT_EQ(header_checksum(header, table), xxh3(joined));
  // The stored checksum itself is not covered.
  auto c = b;
  c[60] = std::byte(0xee);
  EXPECT_EQ(header_checksum(std::span<const std::byte>(c).first<kHeaderSize>(), table), header_checksum(header, table));
}

TEST(Layout, SealHeaderStoresChecksumAndRejectsTableOutside) {
  Header h;
  h.section_count = 1;
  h.file_size = kHeaderSize + kEntrySize;
  auto b = bytes_of(kHeaderSize + kEntrySize);
  encode_header(h, std::span(b).first<kHeaderSize>());
  seal_header(b);
  std::vector<std::byte> joined(b.begin(), b.begin() + 56);
  joined.insert(joined.end(), b.begin() + 64, b.end());
  EXPECT_EQ(get_le(b, 56, 8), xxh3(joined));
  h.section_count = 2;  // table now runs past the end
  encode_header(h, std::span(b).first<kHeaderSize>());
  EXPECT_THROW(seal_header(b), std::out_of_range);
  EXPECT_THROW(seal_header(std::span(b).first(10)), std::out_of_range);
}

TEST(CheckedMath, OverflowIsReportedNotWrapped) {
  const std::uint64_t max = ~std::uint64_t{0};
  EXPECT_EQ(checked_add(max - 1, 1), max);
  EXPECT_EQ(checked_add(max, 1), std::nullopt);
  EXPECT_EQ(checked_mul(std::uint64_t{1} << 32, std::uint64_t{1} << 31), std::uint64_t{1} << 63);
  EXPECT_EQ(checked_mul(std::uint64_t{1} << 32, std::uint64_t{1} << 32), std::nullopt);
  EXPECT_TRUE(range_within(2, 3, 5));
  EXPECT_FALSE(range_within(2, 4, 5));
  EXPECT_TRUE(range_within(5, 0, 5));
  EXPECT_FALSE(range_within(max - 255, 512, max));  // wraps to a small end
}

TEST(Layout, AlignUp) {
  EXPECT_EQ(align_up(0, 256), 0u);
  EXPECT_EQ(align_up(1, 256), 256u);
  EXPECT_EQ(align_up(256, 256), 256u);
  EXPECT_EQ(align_up(257, 256), 512u);
}

}  // namespace
}  // namespace nano::format::test
