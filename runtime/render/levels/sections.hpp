#pragma once
// The package's sections as storage buffers (bindings named after them, shaders/shared/bindings.h):
// read in place from the mapped file where the device can, copied otherwise; a package before 2.2
// or 2.7 gets the drops and core skip levels the baker would have written.
#include <cstdint>

#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;

void build_sections(SceneState& scene);
void write_section_descriptors(const SceneState& scene, VkDescriptorSet set);

}  // namespace nano::levels
