#pragma once
// The flat level (flat_level.hpp): the membrane copies of the triangles nearest the eye as one TLAS
// instance each, chosen again for every eye within the budget set_flatten gives; the µLAS BLAS of a
// compartment with one instance gets its flattened prisms shrunk to points.
#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;
struct EyeUpdate;

void build_flat(SceneState& scene);
void set_flat_eye(SceneState& scene, const EyeUpdate& update);
void write_flat_descriptors(const SceneState& scene, VkDescriptorSet set);

}  // namespace nano::levels
