#pragma once
// Image files of `nanoview render`, each written atomically (temporary name, then rename).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "shared/camera.h"

namespace nano::render {

// "WxH" with 1 ≤ W, H ≤ 16384 (digits only); throws an InputError against `source` saying what is
// wrong. Every command's --size and the viewer's `size` script command read sizes with it.
std::pair<std::uint32_t, std::uint32_t> parse_image_size(std::string_view text, const InputSource& source);

// 8-bit RGBA PNG; `rgba` row-major with row 0 the top row, R in the low byte of each word.
void write_png(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               std::span<const std::uint32_t> rgba);
// Reads an 8-bit RGBA or RGB PNG back (tests, viewer screenshots); throws InputError naming the file.
std::vector<std::uint32_t> read_png(const std::filesystem::path& path, std::uint32_t& width, std::uint32_t& height);

// Greyscale PFM ("Pf", little-endian scale −1, rows bottom to top as the format defines) of the
// depth of each hit: Å along the unit ray, +inf for the background.
void write_depth_pfm(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                     std::span<const gpu::PixelHit> hits);

// The PixelHit records as they are (48 bytes each, little-endian, layout of shared/camera.h),
// row-major from the top row, after a 16-byte header "NUIDS001", width, height (uint32).
void write_ids(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               std::span<const gpu::PixelHit> hits);
// Reads write_ids' file back; throws InputError naming the file for anything else.
std::vector<gpu::PixelHit> read_ids(const std::filesystem::path& path, std::uint32_t& width, std::uint32_t& height);

}  // namespace nano::render
