#include "runtime/render/morton.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace nano::render {
namespace {

// Spreads the low 10 bits of v so that two zero bits separate each.
std::uint32_t spread_bits(std::uint32_t v) {
  v &= 0x3FFu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

}  // namespace

std::vector<std::uint32_t> morton_order(std::span<const VkAabbPositionsKHR> boxes) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  std::vector<double> centres(boxes.size() * 3);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const double c[3] = {0.5 * (double(boxes[i].minX) + boxes[i].maxX), 0.5 * (double(boxes[i].minY) + boxes[i].maxY),
                         0.5 * (double(boxes[i].minZ) + boxes[i].maxZ)};
    for (int a = 0; a < 3; ++a) {
      centres[3 * i + a] = c[a];
      lo[a] = std::min(lo[a], c[a]);
      hi[a] = std::max(hi[a], c[a]);
    }
  }
  std::vector<std::uint32_t> codes(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    std::uint32_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double extent = hi[a] - lo[a];
      const double unit = extent > 0 ? (centres[3 * i + a] - lo[a]) / extent : 0.0;
      const auto q = static_cast<std::uint32_t>(std::clamp(unit * 1023.0, 0.0, 1023.0));
      code |= spread_bits(q) << (2 - a);
    }
    codes[i] = code;
  }
  std::vector<std::uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return codes[a] < codes[b]; });
  return order;
}

}  // namespace nano::render
