#pragma once
// The nLAS: per molecule type a level over its atoms' boxes in molecule space (the exact sphere
// test decides), which the membrane and core copies, the flat level and the medium all end in.
#include <cstdint>

#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;

void build_atoms(SceneState& scene);

}  // namespace nano::levels
