#pragma once
// The core grid: per Wang cube an mLAS of its molecules' bounding spheres' boxes in cube space, and
// per BOUNDARY box what its keep-mask keeps (kept_boxes.hpp). The µLAS holds each compartment's grid
// widened by one box, the region the shader's 3D-DDA walks.
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;

void plan_core(SceneState& scene, std::uint32_t ci);
void build_core(SceneState& scene);
void write_core_descriptors(const SceneState& scene, VkDescriptorSet set);

// Compartment ci's core grid widened by one box (compartment space, one ulp outward); none when it
// holds no soluble molecule.
std::optional<VkAabbPositionsKHR> core_grid_box(const SceneState& scene, std::uint32_t ci);

}  // namespace nano::levels
