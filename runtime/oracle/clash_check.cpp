#include "runtime/oracle/clash_check.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <glm/glm.hpp>

namespace nano::oracle {
namespace {

// 21 bits per axis, offset so negative cells stay distinct; cells beyond ±2^20 alias, which only
// costs extra distance tests, never a missed pair (the distance test decides).
std::uint64_t cell_key(const glm::i64vec3& c) {
  constexpr std::int64_t mask = (std::int64_t{1} << 21) - 1;
  return (std::uint64_t((c.x + (1 << 20)) & mask) << 42) | (std::uint64_t((c.y + (1 << 20)) & mask) << 21) |
         std::uint64_t((c.z + (1 << 20)) & mask);
}

}  // namespace

ClashReport find_clashes(std::span<const ClashAtom> atoms, double factor, std::size_t max_pairs) {
  ClashReport report;
  if (!(factor >= 0) || !std::isfinite(factor)) throw std::invalid_argument("clash factor must be finite and ≥ 0");
  double largest = 0;
  for (const ClashAtom& a : atoms) {
    if (!(a.radius >= 0) || !std::isfinite(a.radius) || !std::isfinite(a.position.x) || !std::isfinite(a.position.y) ||
        !std::isfinite(a.position.z))
      throw std::invalid_argument("clash check: non-finite position or invalid radius");
    largest = std::max(largest, a.radius);
  }
  const double cell = factor * 2 * largest;
  if (atoms.size() < 2 || cell == 0) return report;

  std::vector<glm::i64vec3> cells(atoms.size());
  std::vector<std::uint64_t> keys(atoms.size());
  for (std::size_t i = 0; i < atoms.size(); ++i) {
    cells[i] = glm::i64vec3(glm::floor(atoms[i].position / cell));
    keys[i] = cell_key(cells[i]);
  }
  std::vector<std::size_t> order(atoms.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return keys[x] < keys[y] || (keys[x] == keys[y] && x < y); });
  std::vector<std::uint64_t> sorted_keys(atoms.size());
  for (std::size_t i = 0; i < order.size(); ++i) sorted_keys[i] = keys[order[i]];

  for (std::size_t a = 0; a < atoms.size(); ++a) {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::uint64_t key = cell_key(cells[a] + glm::i64vec3(dx, dy, dz));
          const auto range = std::equal_range(sorted_keys.begin(), sorted_keys.end(), key);
          for (auto it = range.first; it != range.second; ++it) {
            const std::size_t b = order[std::size_t(it - sorted_keys.begin())];
            if (b <= a || atoms[a].copy == atoms[b].copy) continue;
            // A far cell aliasing onto this key is not a neighbour (and is reached again from its own).
            if (glm::any(glm::greaterThan(glm::abs(cells[b] - cells[a]), glm::i64vec3(1)))) continue;
            const double d = glm::distance(atoms[a].position, atoms[b].position);
            const double limit = factor * (atoms[a].radius + atoms[b].radius);
            if (!(d < limit)) continue;
            ++report.count;
            if (report.pairs.size() < max_pairs) report.pairs.push_back({a, b, d, limit});
          }
        }
  }
  std::sort(report.pairs.begin(), report.pairs.end(), [](const Clash& x, const Clash& y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
  return report;
}

}  // namespace nano::oracle
