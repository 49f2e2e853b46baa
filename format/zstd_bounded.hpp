#pragma once
// Decompression of one zstd frame whose size is claimed by untrusted input.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace nano::format {

struct ZstdFrameError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Decompresses `frame`, which must be exactly one zstd frame whose header records a content size
// equal to `raw_size`, and must produce exactly `raw_size` bytes. The output buffer grows with what
// the frame actually produces and never beyond `raw_size`, so neither a lying size nor a bomb can
// make it allocate more than the frame really yields (bounded by the claim). Throws ZstdFrameError.
std::vector<std::byte> inflate_bounded(std::span<const std::byte> frame, std::uint64_t raw_size);

}  // namespace nano::format
