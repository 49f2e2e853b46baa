#pragma once
// The flat level: the membrane copies of the triangles nearest the eye, one TLAS instance each over
// its molecule type's nLAS BLAS, so the hardware traverses them in one query as explicit instancing
// does. Virtual instancing pays per ray for the memory it saves (a membrane copy is met once per
// overlapping prism, placed on the fly, and most are thrown away by the ownership rule); where the
// triangles near the camera fit a memory budget, this buys their rays back. Triangles (of every
// compartment instance) in view are taken nearest first, those facing the eye before those facing
// away, while their copies cover enough pixels to pay for their share of a rebuild and
// the level's device memory (TLAS and copy records) stays within the budget; the µLAS skips the
// prisms of those triangles (one bit each, NANO_B_FLAT_TRIANGLES). The choice is remade for every
// camera; the level is rebuilt when it or the eye changes. Core-grid copies stay virtual.
//
// The copies come from placement::CopyEnumerator (runtime/placement/, which the CPU oracle uses too;
// the renderer does not link the oracle): the shaders' own placement math, with the compartment
// instance transform applied in double, so the flat level draws the copies the virtual path draws,
// with the same identities (FlatCopy → PixelHit).
//
// Precision: TLAS transforms are float, relative to the eye (the camera's float position, as the
// µLAS): the level is rebuilt whenever the eye moves, like the µLAS.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "format/package.hpp"
#include "runtime/vk/acceleration_structure.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::render {

class FlatLevel {
public:
  // `molecule_blas(type)`: the BLAS of molecule type `type`'s atom boxes whose primitive p is the
  // atom orders[levels[type].order_first + p] (GpuScene's nLAS), or nullptr for a type without atoms.
  // `package` must have passed format::validate_semantics and outlive this object.
  FlatLevel(const vk::Device& device, const format::Package& package,
            std::function<const vk::AccelerationStructure*(std::uint32_t)> molecule_blas);
  ~FlatLevel();
  FlatLevel(FlatLevel&&) noexcept;

  // Chooses the triangles to flatten for `camera`: those in view, nearest first (a triangle facing
  // away ranks as if twice as far unless `both_sides`, as when clipping may open the membrane),
  // each while its copies are worth at least 0.05 pixels each (flat_level.cpp says why) and the
  // level's device memory stays within `budget_bytes` (0 empties the level). Rebuilds the level
  // when the choice or the eye changed. Returns true iff the choice changed. Throws
  // std::invalid_argument for a budget with a camera without a finite eye, a field of view or an
  // image. Triangles met for the first time are enumerated (on the CPU, ~7 µs a copy) until
  // `new_copies` copies have been: the rest of the choice waits for later calls, so a caller that
  // must answer input soon (the viewer) bounds the pause.
  bool select(const gpu::Camera& camera, std::uint64_t budget_bytes, bool both_sides,
              std::uint64_t new_copies = ~std::uint64_t{0});

  // Triangle `triangle` (local to its mesh) of compartment instance `instance` is bit
  // first_bit(instance) + triangle of triangle_bits().
  std::uint32_t first_bit(std::uint32_t instance) const;
  bool flattened(std::uint32_t instance, std::uint32_t triangle) const;
  const std::vector<std::uint32_t>& triangle_bits() const;
  bool empty() const;              // no copy flattened: the shader skips the level
  glm::dvec3 anchor() const;       // world point the TLAS transforms are relative to (the last eye)
  std::uint64_t copies() const;    // copies in the level
  std::uint64_t memory_bytes() const;  // TLAS + copy records (0 when empty)
  std::uint64_t triangles() const;     // triangles flattened
  double last_build_seconds() const;   // the last select() that rebuilt: enumeration, upload, TLAS build

  // The level's TLAS and FlatCopy records; valid only when !empty().
  const vk::AccelerationStructure& tlas() const;
  const vk::Buffer& copy_records() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::render
