#pragma once
// Every part of the scene GpuScene puts on the device, declared once, in build order: the package's
// sections, then each acceleration level of the renderer. GpuScene plans every compartment through
// the rows that plan, builds the rows in this order (a row may read what an earlier one built: the
// µLAS reads the membrane's shell offsets, the core's reach and the flat level's triangle bits; the
// medium numbers its copies after the µLAS's instances), writes each row's descriptor bindings and
// hands each row a new eye. A level is added by one row here and its file in this folder, with its
// records in shaders/shared/render_scene.h and bindings.h and its traversal in
// shaders/render/<level>.glsl, included by render.comp (docs/layout.md, "The files an acceleration
// level touches").
#include <cstdint>
#include <span>
#include <string_view>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "format/package_view.hpp"
#include "runtime/render/gpu_scene.hpp"

namespace nano::levels {

struct SceneState;

enum class LevelId : std::uint8_t { sections, atoms, beads, membrane, core, flat, ulas, medium };
inline constexpr std::size_t kLevelCount = 8;

// A new eye (world Å) and, when animated, every compartment instance's transform (empty: the package's).
struct EyeUpdate {
  glm::dvec3 eye;
  std::span<const format::InstanceTransform> moved;
};

struct LevelEntry {
  LevelId id;
  std::string_view name;     // as docs and reports name it
  std::string_view summary;  // one line: what it holds
  double render::LoadReport::*seconds;  // the load timer its build counts in
  // Its part of compartment `ci`'s RenderCompartment (SceneState::render_compartments), before any
  // row builds; throws nano::InputError for what it cannot render. nullptr: none.
  void (*plan)(SceneState& scene, std::uint32_t ci);
  void (*build)(SceneState& scene);
  // Its bindings of the render pipeline's set (shaders/shared/bindings.h). nullptr: none of its own.
  void (*write_descriptors)(const SceneState& scene, VkDescriptorSet set);
  // What it rebuilds for a new eye, in table order. nullptr: nothing.
  void (*set_eye)(SceneState& scene, const EyeUpdate& update);
};

std::span<const LevelEntry> level_table();

}  // namespace nano::levels
