// Decompression of untrusted zstd frames: exact sizes, bombs and lies about sizes.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <zstd.h>

#include "format/layout.hpp"
#include "format/writer.hpp"
#include "format/zstd_bounded.hpp"
#include "tests/format/package_bytes.hpp"

// GCC cannot see that this malloc-based operator new pairs with the free-based delete below.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
// Largest single operator-new request, to check that no buffer follows an unverified claim.
static std::atomic<std::size_t> g_largest_allocation{0};
void* operator new(std::size_t n) {
  std::size_t seen = g_largest_allocation.load();
  while (n > seen && !g_largest_allocation.compare_exchange_weak(seen, n)) {}
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace nano::format::test {
namespace {

// A zstd frame of `size` zero bytes, its header recording the size, compressed in 1 MiB steps so
// the test never holds the whole input.
std::vector<std::byte> zero_frame(std::uint64_t size) {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, 1);
  ZSTD_CCtx_setPledgedSrcSize(cctx, size);
  const std::vector<char> zeros(1 << 20, 0);
  std::vector<std::byte> out(ZSTD_CStreamOutSize());
  std::vector<std::byte> frame;
  std::uint64_t left = size;
  for (;;) {
    const std::size_t chunk = std::min<std::uint64_t>(left, zeros.size());
    left -= chunk;
    ZSTD_inBuffer in{zeros.data(), chunk, 0};
    const ZSTD_EndDirective mode = left ? ZSTD_e_continue : ZSTD_e_end;
    std::size_t remaining;
    do {
      ZSTD_outBuffer o{out.data(), out.size(), 0};
      remaining = ZSTD_compressStream2(cctx, &o, &in, mode);
      EXPECT_FALSE(ZSTD_isError(remaining));
      frame.insert(frame.end(), out.begin(), out.begin() + o.pos);
    } while (mode == ZSTD_e_end ? remaining != 0 : in.pos < in.size);
    if (!left) break;
  }
  ZSTD_freeCCtx(cctx);
  return frame;
}

// Rewrites the content-size field of a frame header (RFC 8878 §3.1.1.1) to `claim`, keeping its width.
void patch_content_size(std::vector<std::byte>& frame, std::uint64_t claim) {
  const unsigned fhd = std::to_integer<unsigned>(frame[4]);
  const unsigned fcs_flag = fhd >> 6, single_segment = (fhd >> 5) & 1, dict_flag = fhd & 3;
  std::size_t at = 5 + (single_segment ? 0 : 1) + (dict_flag ? (1u << (dict_flag - 1)) : 0);
  const int width = fcs_flag == 0 ? 1 : (1 << fcs_flag);
  if (width == 2) claim -= 256;  // the 2-byte form is stored minus 256
  put_le(frame, at, width, claim);
}

TEST(ZstdBounded, ExactFrameRoundTrips) {
  const std::vector<std::byte> frame = zero_frame(3 << 20);
  const std::vector<std::byte> out = inflate_bounded(frame, 3 << 20);
  EXPECT_EQ(out.size(), 3u << 20);
  EXPECT_TRUE(std::all_of(out.begin(), out.end(), [](std::byte b) { return b == std::byte{0}; }));
}

TEST(ZstdBounded, FrameThatClaimsLessThanItHoldsIsABombAndStaysSmall) {
  std::vector<std::byte> frame = zero_frame(std::uint64_t{256} << 20);  // 256 MiB of zeros in a few KiB
  ASSERT_LT(frame.size(), 64u << 10);
  patch_content_size(frame, 1 << 16);
  ASSERT_EQ(ZSTD_getFrameContentSize(frame.data(), frame.size()), 1u << 16);
  g_largest_allocation = 0;
  EXPECT_THROW(inflate_bounded(frame, 1 << 16), ZstdFrameError);
  EXPECT_LE(g_largest_allocation.load(), std::size_t{1} << 20);
}

TEST(ZstdBounded, FrameThatHoldsLessThanItClaimsAllocatesOnlyWhatItYields) {
  std::vector<std::byte> frame = zero_frame(4096);
  patch_content_size(frame, std::uint64_t{1} << 30);
  g_largest_allocation = 0;
  EXPECT_THROW(inflate_bounded(frame, std::uint64_t{1} << 30), ZstdFrameError);
  EXPECT_LE(g_largest_allocation.load(), std::size_t{1} << 21);
}

TEST(ZstdBounded, RejectsMismatchedClaimTrailingBytesMissingSizeAndGarbage) {
  const std::vector<std::byte> frame = zero_frame(1000);
  EXPECT_THROW(inflate_bounded(frame, 999), ZstdFrameError);
  auto trailing = frame;
  trailing.push_back(std::byte{0});
  EXPECT_THROW(inflate_bounded(trailing, 1000), ZstdFrameError);
  EXPECT_THROW(inflate_bounded(std::span(frame).first(frame.size() - 1), 1000), ZstdFrameError);
  std::vector<std::byte> garbage(64, std::byte{0x5a});
  EXPECT_THROW(inflate_bounded(garbage, 1000), ZstdFrameError);
  // A frame without a recorded content size.
  std::vector<char> raw(1000, 'x');
  std::vector<std::byte> unsized(ZSTD_compressBound(raw.size()));
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 0);
  ZSTD_outBuffer o{unsized.data(), unsized.size(), 0};
  ZSTD_inBuffer in{raw.data(), raw.size(), 0};
  ASSERT_EQ(ZSTD_compressStream2(cctx, &o, &in, ZSTD_e_end), 0u);  // unknown size: streaming API
  ZSTD_freeCCtx(cctx);
  unsized.resize(o.pos);
  ASSERT_EQ(ZSTD_getFrameContentSize(unsized.data(), unsized.size()), ZSTD_CONTENTSIZE_UNKNOWN);
  EXPECT_THROW(inflate_bounded(unsized, 1000), ZstdFrameError);
}

TEST(ZstdBounded, BombInsideAPackageIsRejectedAsDecompression) {
  // A package whose zstd section inflates to 256 MiB while claiming 64 KiB.
  std::vector<std::byte> frame = zero_frame(std::uint64_t{256} << 20);
  patch_content_size(frame, 1 << 16);
  std::vector<std::byte> raw(1 << 16);  // what the writer would have compressed
  const SectionSource src{static_cast<std::uint32_t>(SectionKind::occupancy), raw, Compression::zstd_if_smaller, 0};
  std::vector<std::byte> pkg = build_package(std::span(&src, 1));
  ASSERT_EQ(get_le(pkg, entry_at(0) + 4, 2), 1u);
  const std::uint64_t off = get_le(pkg, entry_at(0) + 8, 8);
  pkg.resize(off);
  pkg.insert(pkg.end(), frame.begin(), frame.end());
  put_le(pkg, 16, 8, pkg.size());
  put_le(pkg, entry_at(0) + 16, 8, frame.size());
  put_le(pkg, entry_at(0) + 32, 8, xxh3(frame));
  seal_header(pkg);
  g_largest_allocation = 0;
  EXPECT_EQ(broken_rule(pkg), Rule::decompression);
  EXPECT_LE(g_largest_allocation.load(), pkg.size() + (std::size_t{1} << 20));
}

}  // namespace
}  // namespace nano::format::test
