#include "bake/tiles/copy_neighbourhood.hpp"

#include <algorithm>
#include <cmath>

namespace nano::tiles {

CopyNeighbourhood::CopyNeighbourhood(const std::vector<CollisionShape>& shapes, float cell)
    : shapes_(shapes), cell_(cell) {}

uint64_t CopyNeighbourhood::key(const glm::ivec3& c) const {
  const auto u = [](int v) { return static_cast<uint64_t>(static_cast<uint32_t>(v) & 0x1FFFFFu); };
  return u(c.x) | (u(c.y) << 21) | (u(c.z) << 42);
}

size_t CopyNeighbourhood::add(uint32_t type, const Pose& pose) {
  const glm::ivec3 c(glm::floor(pose.position / cell_));
  buckets_[key(c)].push_back(static_cast<uint32_t>(copies_.size()));
  copies_.push_back({type, pose});
  max_radius_ = std::max(max_radius_, shapes_[type].radius());
  max_height_ = std::max(max_height_, std::abs(pose.position.z) + shapes_[type].radius());
  return copies_.size() - 1;
}

void CopyNeighbourhood::retire(size_t index) {
  if (index < copies_.size()) copies_[index].retired = true;
}

bool CopyNeighbourhood::collides(uint32_t type, const Pose& pose, const ClashRule& rule) const {
  const CollisionShape& shape = shapes_[type];
  const float height = std::max(max_height_, std::abs(pose.position.z) + shape.radius());
  const float reach = (shape.radius() + max_radius_) / rule.closest_scale(height);
  const glm::ivec3 lo(glm::floor((pose.position - reach) / cell_));
  const glm::ivec3 hi(glm::floor((pose.position + reach) / cell_));
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const auto it = buckets_.find(key({x, y, z}));
        if (it == buckets_.end()) continue;
        for (uint32_t i : it->second) {
          const Copy& other = copies_[i];
          if (other.retired) continue;
          if (copies_collide(shape, pose, shapes_[other.type], other.pose, rule)) return true;
        }
      }
  return false;
}

}  // namespace nano::tiles
