#include "runtime/vk/embedded_shaders.hpp"

#define XXH_STATIC_LINKING_ONLY  // XXH3_state_t on the stack
#include <xxhash.h>

// The modules nano_shaders embeds (cmake/Shaders.cmake names them nano_spv_<stem>). A module
// missing here only means its changes keep the old cache file, whose stale entries cost space,
// never correctness: the driver keys its entries by the SPIR-V itself.
extern const std::uint32_t nano_spv_smoke_ray_query_comp[];
extern const std::size_t nano_spv_smoke_ray_query_comp_words;
extern const std::uint32_t nano_spv_render_comp[];
extern const std::size_t nano_spv_render_comp_words;
extern const std::uint32_t nano_spv_instanced_comp[];
extern const std::size_t nano_spv_instanced_comp_words;
extern const std::uint32_t nano_spv_render_nano_no_effects_comp[];
extern const std::size_t nano_spv_render_nano_no_effects_comp_words;

namespace nano::vk {

std::uint64_t hash_spirv(std::span<const SpirvCode> modules) {
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  for (const SpirvCode& module : modules) {
    const std::uint64_t words = module.word_count;
    XXH3_64bits_update(&state, &words, sizeof words);
    XXH3_64bits_update(&state, module.words, module.word_count * sizeof *module.words);
  }
  return XXH3_64bits_digest(&state);
}

std::uint64_t embedded_shader_hash() {
  const SpirvCode modules[] = {
      {nano_spv_smoke_ray_query_comp, nano_spv_smoke_ray_query_comp_words},
      {nano_spv_render_comp, nano_spv_render_comp_words},
      {nano_spv_instanced_comp, nano_spv_instanced_comp_words},
      {nano_spv_render_nano_no_effects_comp, nano_spv_render_nano_no_effects_comp_words},
  };
  return hash_spirv(modules);
}

}  // namespace nano::vk
