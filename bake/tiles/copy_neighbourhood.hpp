#pragma once
// The copies a candidate must not touch, hashed by centre so a test only visits copies whose
// bounding spheres can reach the candidate.
#include "bake/tiles/collision_shape.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace nano::tiles {

class CopyNeighbourhood {
public:
  // `shapes` must outlive this object; `cell` is the hash cell edge (Å), > 0.
  CopyNeighbourhood(const std::vector<CollisionShape>& shapes, float cell);

  // Returns the copy's index, for retire.
  size_t add(uint32_t type, const Pose& pose);
  // The copy no longer counts (a place being given to another molecule); its index stays taken.
  void retire(size_t index);
  bool collides(uint32_t type, const Pose& pose, const ClashRule& rule) const;
  size_t size() const { return copies_.size(); }

private:
  struct Copy {
    uint32_t type;
    Pose pose;
    bool retired = false;
  };
  uint64_t key(const glm::ivec3& c) const;
  const std::vector<CollisionShape>& shapes_;
  float cell_;
  float max_radius_ = 0.f;
  float max_height_ = 0.f;  // max |z| + radius over the copies: bounds the curvature's shrink
  std::vector<Copy> copies_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> buckets_;
};

}  // namespace nano::tiles
