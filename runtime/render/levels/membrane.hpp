#pragma once
// The membrane shell: per triangle that owns molecules a prism (its µLAS box, with the shell offsets
// of the chosen mode), per Wang square and distortion class an mLAS of molecule boxes widened to hold
// every copy wherever a triangle places it (placement/membrane_distortion.hpp), per compartment a
// repLAS of its replication slots, and with --levels 2 the paper's per-square atom BLASes.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;

void plan_membrane(SceneState& scene, std::uint32_t ci);
void build_membrane(SceneState& scene);
void write_membrane_descriptors(const SceneState& scene, VkDescriptorSet set);

// Compartment ci's prism boxes (compartment space, one ulp outward) and the local triangle each
// belongs to, in mesh order; none without a membrane.
void membrane_prisms(const SceneState& scene, std::uint32_t ci, std::vector<VkAabbPositionsKHR>& prisms,
                     std::vector<std::uint32_t>& triangles);

}  // namespace nano::levels
