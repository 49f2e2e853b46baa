#include "bake/tiles/bilayer_footprint.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

namespace nano::tiles {

double leaflet_footprint(const MoleculeType& type, const Instance& copy, LeafletSlab slab, float cell) {
  struct Disc {
    glm::vec2 centre;
    float radius;
  };
  // An atom meets the slab where its sphere crosses it; the widest cross-section inside the slab is
  // at the slab face nearest its centre (or through the centre when that lies inside).
  std::vector<Disc> discs;
  const glm::mat3 rotation = glm::mat3_cast(glm::normalize(copy.rotation));
  glm::vec2 lo(INFINITY), hi(-INFINITY);
  for (const AtomSphere& a : type.atoms) {
    const glm::vec3 c = copy.position + rotation * a.centre;
    const float outside = c.z < slab.z_low ? slab.z_low - c.z : (c.z > slab.z_high ? c.z - slab.z_high : 0.f);
    if (outside >= a.radius) continue;
    const float r = std::sqrt(a.radius * a.radius - outside * outside);
    discs.push_back({glm::vec2(c), r});
    lo = glm::min(lo, glm::vec2(c) - r);
    hi = glm::max(hi, glm::vec2(c) + r);
  }
  if (discs.empty()) return 0.0;
  const int nx = static_cast<int>(std::ceil((hi.x - lo.x) / cell)) + 1;
  const int ny = static_cast<int>(std::ceil((hi.y - lo.y) / cell)) + 1;
  std::vector<char> covered(static_cast<std::size_t>(nx) * ny, 0);
  for (const Disc& d : discs) {
    const int x0 = std::max(0, static_cast<int>(std::floor((d.centre.x - d.radius - lo.x) / cell)));
    const int x1 = std::min(nx - 1, static_cast<int>(std::ceil((d.centre.x + d.radius - lo.x) / cell)));
    const int y0 = std::max(0, static_cast<int>(std::floor((d.centre.y - d.radius - lo.y) / cell)));
    const int y1 = std::min(ny - 1, static_cast<int>(std::ceil((d.centre.y + d.radius - lo.y) / cell)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const glm::vec2 p = lo + cell * (glm::vec2(static_cast<float>(x), static_cast<float>(y)) + 0.5f);
        const glm::vec2 d2 = p - d.centre;
        if (glm::dot(d2, d2) <= d.radius * d.radius) covered[static_cast<std::size_t>(y) * nx + x] = 1;
      }
  }
  const auto cells = std::count(covered.begin(), covered.end(), char{1});
  return static_cast<double>(cells) * cell * cell;
}

}  // namespace nano::tiles
