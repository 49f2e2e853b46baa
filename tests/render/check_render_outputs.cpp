// Checks the files of one `nanoview render --depth --ids` run against each other and against the
// oracle's hit rule: every pixel whose ids name an atom has a finite positive depth and a colour
// that is not the background; every background pixel has depth +inf, no ids and the background
// colour; the PFM, the ids and the PNG have the same size. Usage: check_render_outputs PNG PFM IDS
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "runtime/render/image_io.hpp"

int main(int argc, char** argv) {
  if (argc != 4) return std::fprintf(stderr, "usage: check_render_outputs PNG PFM IDS\n"), 2;
  std::uint32_t w = 0, h = 0;
  const std::vector<std::uint32_t> rgba = nano::render::read_png(argv[1], w, h);
  std::ifstream ids_file(argv[3], std::ios::binary);
  std::string ids((std::istreambuf_iterator<char>(ids_file)), std::istreambuf_iterator<char>());
  std::uint32_t iw = 0, ih = 0;
  if (ids.size() < 16 || ids.compare(0, 8, "NUIDS001") != 0) return std::fprintf(stderr, "ids: bad header\n"), 1;
  std::memcpy(&iw, ids.data() + 8, 4);
  std::memcpy(&ih, ids.data() + 12, 4);
  if (iw != w || ih != h || ids.size() != 16 + std::size_t(w) * h * sizeof(nano::gpu::PixelHit))
    return std::fprintf(stderr, "ids: size %ux%u does not match the PNG's %ux%u\n", iw, ih, w, h), 1;
  std::vector<nano::gpu::PixelHit> hits(std::size_t(w) * h);
  std::memcpy(hits.data(), ids.data() + 16, ids.size() - 16);
  std::ifstream pfm_file(argv[2], std::ios::binary);
  std::string pfm((std::istreambuf_iterator<char>(pfm_file)), std::istreambuf_iterator<char>());
  const std::string header = "Pf\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
  if (pfm.compare(0, header.size(), header) != 0 || pfm.size() != header.size() + 4 * hits.size())
    return std::fprintf(stderr, "pfm: bad header or size\n"), 1;
  std::size_t bad = 0, hit = 0;
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      const nano::gpu::PixelHit& p = hits[std::size_t(y) * w + x];
      float depth;
      std::memcpy(&depth, pfm.data() + header.size() + 4 * (std::size_t(h - 1 - y) * w + x), 4);
      const bool background_colour = (rgba[std::size_t(y) * w + x] & 0xFFFFFFu) == 0xFFFFFFu;
      const bool ok = p.atom == nano::gpu::kNoHit
                          ? std::isinf(depth) && depth > 0 && p.copy_number_lo == nano::gpu::kNoHit && background_colour
                          : std::isfinite(depth) && depth > 0 && depth == p.depth && !background_colour &&
                                p.compartment_instance != nano::gpu::kNoHit;
      hit += p.atom != nano::gpu::kNoHit;
      if (!ok && bad++ < 5) std::fprintf(stderr, "pixel (%u, %u) inconsistent: atom %u depth %g\n", x, y, p.atom, depth);
    }
  std::printf("%ux%u: %zu pixels hit, %zu inconsistent\n", w, h, hit, bad);
  return bad == 0 && hit > 0 ? 0 : 1;
}
