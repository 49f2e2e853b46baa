#pragma once
// The medium (shared/medium.h): the plasma between the cells as one periodic region of Wang cubes,
// its copies kept clear of every compartment instance by their exclusion fields (region-space boxes
// in one BLAS, primitive = instance), and the eye's box in the region for every frame.
#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;
struct EyeUpdate;

void build_medium(SceneState& scene);
void set_medium_eye(SceneState& scene, const EyeUpdate& update);
void write_medium_descriptors(const SceneState& scene, VkDescriptorSet set);

}  // namespace nano::levels
