#pragma once
// One number for "these shaders": the persistent pipeline cache is keyed by it, so a build with
// other shaders starts a file of its own instead of growing one with entries nobody asks for.
#include <cstdint>
#include <span>

#include "runtime/vk/compute_pipeline.hpp"

namespace nano::vk {

// XXH3-64 of the modules in order, each preceded by its word count (so a word moved from one
// module to the next changes the hash too).
std::uint64_t hash_spirv(std::span<const SpirvCode> modules);

// hash_spirv of every SPIR-V module the program embeds (shaders/CMakeLists.txt).
std::uint64_t embedded_shader_hash();

}  // namespace nano::vk
