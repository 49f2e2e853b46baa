#include "runtime/render/levels/flat.hpp"

#include <memory>
#include <vector>

#include "runtime/render/levels/level_table.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/render/levels/ulas.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"

namespace nano::levels {
namespace {

// After the flat level's choice changed: a compartment with one instance gets its µLAS BLAS again
// with each flattened triangle's prism box shrunk to the point at its centre, so traversal all
// but never meets it (a ray through that very point is a candidate the shader skips by the
// triangle's bit; a NaN box, "inactive" by the Vulkan spec, lost neighbouring prisms on
// lavapipe). Compartments shared by several instances keep every prism; the shader skips
// flattened ones by their bit, each µLAS candidate still costing a callback.
void deactivate_flattened_prisms(SceneState& s) {
  std::vector<std::uint32_t> instance_count(s.compartments.size(), 0), sole_instance(s.compartments.size(), 0);
  for (std::uint32_t i = 0; i < s.compartment_instances.size(); ++i)
    ++instance_count[s.compartment_instances[i].compartment], sole_instance[s.compartment_instances[i].compartment] = i;
  for (std::uint32_t ci = 0; ci < s.compartments.size(); ++ci) {
    if (instance_count[ci] != 1 || s.render_compartments[ci].counts.z == 0) continue;
    const gpu::RenderCompartment& rc = s.render_compartments[ci];
    std::vector<VkAabbPositionsKHR> boxes = s.compartment_boxes[ci];
    for (std::uint32_t prim = 0; prim < rc.counts.z; ++prim)
      if (s.flat->flattened(sole_instance[ci], s.orders[rc.counts.w + prim])) {
        VkAabbPositionsKHR& b = boxes[prim];
        const float x = 0.5f * (b.minX + b.maxX), y = 0.5f * (b.minY + b.maxY), z = 0.5f * (b.minZ + b.maxZ);
        b = {x, y, z, x, y, z};
      }
    build_compartment_blas(s, ci, boxes);
  }
}

}  // namespace

// Empty until a budget asks for copies; its copies are instances of the atoms row's nLAS BLASes.
void build_flat(SceneState& s) {
  s.flat = std::make_unique<render::FlatLevel>(s.device, s.package, [&s](std::uint32_t type) -> const vk::AccelerationStructure* {
    return type < s.molecules.size() && s.level_records[type].count > 0 ? &s.levels[type].blas : nullptr;
  });
  s.flat_triangle_buffer = vk::Buffer(s.device, s.flat->triangle_bits().size() * sizeof(std::uint32_t),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
  s.flat_triangle_buffer.write(std::as_bytes(std::span(s.flat->triangle_bits())));
  const gpu::FlatCopy none{};
  s.flat_placeholder = s.storage(std::as_bytes(std::span(&none, 1)));
  s.report.memory.derived += s.flat_placeholder.size() + s.flat_triangle_buffer.size();
}

// Moved instances (animation) trace every copy virtually: the level holds copies at the package's poses.
void set_flat_eye(SceneState& s, const EyeUpdate& u) {
  if (!s.flat->select(s.flatten_camera, u.moved.empty() ? s.flatten_budget : 0, s.flatten_both_sides, s.flatten_new_copies))
    return;
  s.flat_triangle_buffer.write(std::as_bytes(std::span(s.flat->triangle_bits())));
  deactivate_flattened_prisms(s);
  s.report.memory.flat = s.flat->memory_bytes();
  s.report.flattened_copies = s.flat->copies();
  s.report.flattened_triangles = s.flat->triangles();
  s.report.flat_seconds = s.flat->last_build_seconds();
}

// While empty, the µLAS stands in for its TLAS and a zero record for its copies (no binding may be empty).
void write_flat_descriptors(const SceneState& s, VkDescriptorSet set) {
  const VkDevice d = s.device.handle();
  const bool flat = !s.flat->empty();
  vk::write_acceleration_structure(d, set, gpu::NANO_B_FLAT_TLAS, flat ? s.flat->tlas() : s.ulas);
  vk::write_storage_buffer(d, set, gpu::NANO_B_FLAT_COPIES, flat ? s.flat->copy_records() : s.flat_placeholder);
  vk::write_storage_buffer(d, set, gpu::NANO_B_FLAT_TRIANGLES, s.flat_triangle_buffer);
}

}  // namespace nano::levels
