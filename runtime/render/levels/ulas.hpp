#pragma once
// The µLAS: per compartment a BLAS of its membrane prisms (Morton-sorted) and its core grid's box;
// one TLAS over the compartment instances, rebuilt for every eye with translations relative to it
// (precision far from the origin), and per instance the record the shader enters compartment space by
// (RenderInstance: the eye as a double computed float pair, its copy numbers' base).
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;
struct EyeUpdate;

void build_ulas(SceneState& scene);
void set_ulas_eye(SceneState& scene, const EyeUpdate& update);
void write_ulas_descriptors(const SceneState& scene, VkDescriptorSet set);

// (Re)builds compartment ci's BLAS from `boxes` (the flat level shrinks flattened prisms).
void build_compartment_blas(SceneState& scene, std::uint32_t ci, const std::vector<VkAabbPositionsKHR>& boxes);

}  // namespace nano::levels
