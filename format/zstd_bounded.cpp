#include "format/zstd_bounded.hpp"

#include <algorithm>
#include <memory>
#include <string>
#include <zstd.h>

namespace nano::format {
namespace {

constexpr std::uint64_t kFirstChunk = std::uint64_t{1} << 20;
// zstd's default decoder window cap (128 MiB): a frame asking for more is refused, not obeyed.
constexpr int kWindowLogMax = 27;

struct DctxFree {
  void operator()(ZSTD_DCtx* d) const { ZSTD_freeDCtx(d); }
};

void check_frame_header(std::span<const std::byte> frame, std::uint64_t raw_size) {
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) throw ZstdFrameError("not a zstd frame");
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) throw ZstdFrameError("zstd frame does not record its content size");
  if (content != raw_size)
    throw ZstdFrameError("zstd frame content size " + std::to_string(content) + " differs from the claimed raw size " +
                         std::to_string(raw_size));
  const std::size_t frame_size = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
  if (ZSTD_isError(frame_size)) throw ZstdFrameError(std::string("zstd frame: ") + ZSTD_getErrorName(frame_size));
  if (frame_size != frame.size()) throw ZstdFrameError("stored bytes are not exactly one zstd frame");
}

}  // namespace

std::vector<std::byte> inflate_bounded(std::span<const std::byte> frame, std::uint64_t raw_size) {
  check_frame_header(frame, raw_size);
  std::unique_ptr<ZSTD_DCtx, DctxFree> dctx(ZSTD_createDCtx());
  if (!dctx) throw std::bad_alloc();
  ZSTD_DCtx_setParameter(dctx.get(), ZSTD_d_windowLogMax, kWindowLogMax);

  std::vector<std::byte> out(std::min(raw_size, kFirstChunk));
  ZSTD_inBuffer in{frame.data(), frame.size(), 0};
  std::size_t produced = 0;
  for (;;) {
    if (produced == out.size()) {
      if (out.size() == raw_size) break;
      out.resize(std::min<std::uint64_t>(raw_size, out.size() * 2));
    }
    ZSTD_outBuffer o{out.data(), out.size(), produced};
    const std::size_t before_in = in.pos;
    const std::size_t r = ZSTD_decompressStream(dctx.get(), &o, &in);
    if (ZSTD_isError(r)) throw ZstdFrameError(std::string("zstd: ") + ZSTD_getErrorName(r));
    const bool progressed = o.pos != produced || in.pos != before_in;
    produced = o.pos;
    if (r == 0) {
      if (produced != raw_size || in.pos != in.size)
        throw ZstdFrameError("zstd frame yields " + std::to_string(produced) + " bytes, not the claimed " +
                             std::to_string(raw_size));
      return out;
    }
    if (!progressed && produced < out.size()) throw ZstdFrameError("zstd frame is truncated");
  }
  // The claimed size is reached but the frame is not finished: one more byte would be a bomb.
  std::byte probe{};
  for (;;) {
    ZSTD_outBuffer o{&probe, 1, 0};
    const std::size_t before_in = in.pos;
    const std::size_t r = ZSTD_decompressStream(dctx.get(), &o, &in);
    if (ZSTD_isError(r)) throw ZstdFrameError(std::string("zstd: ") + ZSTD_getErrorName(r));
    if (o.pos != 0) throw ZstdFrameError("zstd frame inflates beyond the claimed raw size " + std::to_string(raw_size));
    if (r == 0) {
      if (in.pos != in.size) throw ZstdFrameError("bytes follow the zstd frame");
      return out;
    }
    if (in.pos == before_in) throw ZstdFrameError("zstd frame is truncated");
  }
}

}  // namespace nano::format
