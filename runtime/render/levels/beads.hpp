#pragma once
// The level of detail: per molecule type a level over the beads the baker stored for it, which a
// copy too small on screen is traced through instead of its atoms (--lod).
#include <cstdint>

#include <vulkan/vulkan.h>

namespace nano::levels {

struct SceneState;

void build_beads(SceneState& scene);

}  // namespace nano::levels
