#pragma once
// Primitive order for acceleration-structure builds. Lavapipe splits BVH nodes at the median in the
// order it is given (../shared/DESIGN.md, "Lavapipe facts"), so AABBs are sorted along a Morton
// curve before every build: ~10× faster frames there, harmless on drivers that sort themselves.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace nano::render {

// Permutation p such that boxes[p[0]], boxes[p[1]], ... follow the 30-bit Morton code of the box
// centres quantised over their common bounds (ties by index, so the order is deterministic).
std::vector<std::uint32_t> morton_order(std::span<const VkAabbPositionsKHR> boxes);

}  // namespace nano::render
