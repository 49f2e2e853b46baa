#include "runtime/render/image_io.hpp"

#include <charconv>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <png.h>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace nano::render {
namespace {

void check_size(std::size_t count, std::uint32_t width, std::uint32_t height, const char* what) {
  if (width == 0 || height == 0 || count != std::size_t(width) * height)
    throw std::invalid_argument(std::string(what) + ": pixel count does not match width × height");
}

[[noreturn]] void png_fail(png_structp png, png_const_charp message) {
  throw InputError(static_cast<const char*>(png_get_error_ptr(png)), "", std::string("PNG: ") + message);
}

}  // namespace

void write_png(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               std::span<const std::uint32_t> rgba) {
  check_size(rgba.size(), width, height, "write_png");
  const std::string name = path.string();
  write_file_atomically(path, [&](std::FILE* file) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, const_cast<char*>(name.c_str()), png_fail, nullptr);
    png_infop info = png_create_info_struct(png);
    try {
      png_init_io(png, file);
      png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                   PNG_FILTER_TYPE_DEFAULT);
      png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
      png_write_info(png, info);
      std::vector<std::uint8_t> row(std::size_t(width) * 4);
      for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) {
          const std::uint32_t v = rgba[std::size_t(y) * width + x];
          for (int c = 0; c < 4; ++c) row[4 * x + c] = std::uint8_t(v >> (8 * c));
        }
        png_write_row(png, row.data());
      }
      png_write_end(png, nullptr);
    } catch (...) {
      png_destroy_write_struct(&png, &info);
      throw;
    }
    png_destroy_write_struct(&png, &info);
  });
}

std::vector<std::uint32_t> read_png(const std::filesystem::path& path, std::uint32_t& width, std::uint32_t& height) {
  const std::string name = path.string();
  std::FILE* file = std::fopen(name.c_str(), "rb");
  if (!file) throw InputError(name, "", "cannot open for reading");
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, const_cast<char*>(name.c_str()), png_fail, nullptr);
  png_infop info = png_create_info_struct(png);
  std::vector<std::uint32_t> out;
  try {
    png_init_io(png, file);
    png_read_info(png, info);
    width = png_get_image_width(png, info);
    height = png_get_image_height(png, info);
    const int type = png_get_color_type(png, info);
    if (png_get_bit_depth(png, info) != 8 || (type != PNG_COLOR_TYPE_RGB && type != PNG_COLOR_TYPE_RGB_ALPHA))
      throw InputError(name, "", "only 8-bit RGB or RGBA PNGs are read");
    if (type == PNG_COLOR_TYPE_RGB) png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    png_read_update_info(png, info);
    std::vector<std::uint8_t> row(std::size_t(width) * 4);
    out.resize(std::size_t(width) * height);
    for (std::uint32_t y = 0; y < height; ++y) {
      png_read_row(png, row.data(), nullptr);
      for (std::uint32_t x = 0; x < width; ++x) {
        std::uint32_t v = 0;
        for (int c = 0; c < 4; ++c) v |= std::uint32_t(row[4 * x + c]) << (8 * c);
        out[std::size_t(y) * width + x] = v;
      }
    }
  } catch (...) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(file);
    throw;
  }
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(file);
  return out;
}

void write_depth_pfm(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
                     std::span<const gpu::PixelHit> hits) {
  check_size(hits.size(), width, height, "write_depth_pfm");
  std::string bytes = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  for (std::uint32_t r = 0; r < height; ++r) {
    const std::uint32_t y = height - 1 - r;  // PFM rows run from the bottom up
    for (std::uint32_t x = 0; x < width; ++x) {
      const float d = hits[std::size_t(y) * width + x].depth;
      char le[4];
      std::memcpy(le, &d, 4);  // little-endian host (x86-64, AArch64 LE); PFM scale −1 says so
      bytes.append(le, 4);
    }
  }
  write_file_atomically(path, std::as_bytes(std::span(bytes.data(), bytes.size())));
}

std::pair<std::uint32_t, std::uint32_t> parse_image_size(std::string_view text, const InputSource& source) {
  const auto number = [](std::string_view digits, std::uint32_t& value) {
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    return !digits.empty() && error == std::errc() && end == digits.data() + digits.size();
  };
  const auto x = text.find('x');
  std::uint32_t w = 0, h = 0;
  if (x == std::string_view::npos || !number(text.substr(0, x), w) || !number(text.substr(x + 1), h) || w == 0 || h == 0 ||
      w > 16384 || h > 16384)
    source.fail("expected a size WxH with 1 ≤ W, H ≤ 16384, got '" + std::string(text) + "'");
  return {w, h};
}

void write_ids(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               std::span<const gpu::PixelHit> hits) {
  check_size(hits.size(), width, height, "write_ids");
  std::vector<std::byte> bytes(16 + hits.size_bytes());
  std::memcpy(bytes.data(), "NUIDS001", 8);
  std::memcpy(bytes.data() + 8, &width, 4);
  std::memcpy(bytes.data() + 12, &height, 4);
  std::memcpy(bytes.data() + 16, hits.data(), hits.size_bytes());
  write_file_atomically(path, bytes);
}

std::vector<gpu::PixelHit> read_ids(const std::filesystem::path& path, std::uint32_t& width, std::uint32_t& height) {
  const std::string name = path.string();
  std::FILE* file = std::fopen(name.c_str(), "rb");
  if (!file) throw InputError(name, "", "cannot open for reading");
  char header[16];
  const bool whole_header = std::fread(header, 1, 16, file) == 16;
  std::vector<gpu::PixelHit> hits;
  if (whole_header && std::memcmp(header, "NUIDS001", 8) == 0) {
    std::memcpy(&width, header + 8, 4);
    std::memcpy(&height, header + 12, 4);
    if (width > 0 && height > 0 && width <= 16384 && height <= 16384) {
      hits.resize(std::size_t(width) * height);
      const std::size_t got = std::fread(hits.data(), sizeof(gpu::PixelHit), hits.size(), file);
      const bool at_end = std::fgetc(file) == EOF;
      std::fclose(file);
      if (got != hits.size() || !at_end)
        throw InputError(name, "", "expected exactly " + std::to_string(hits.size()) + " hit records of 48 bytes after the header");
      return hits;
    }
  }
  std::fclose(file);
  throw InputError(name, "", "not an ids file (header \"NUIDS001\", width and height in [1, 16384])");
}

}  // namespace nano::render
