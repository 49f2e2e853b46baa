#include "runtime/render/levels/core.hpp"

#include <algorithm>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "runtime/render/kept_boxes.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"

namespace nano::levels {

using glm::dvec3;
using glm::vec3;

void plan_core(SceneState& s, std::uint32_t ci) {
  const gpu::Compartment& c = s.compartments[ci];
  if (c.soluble_recipe == gpu::NANO_NO_INDEX) return;
  gpu::RenderCompartment& rc = s.render_compartments[ci];
  const double B = c.grid_min.w;
  dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  std::uint32_t largest = 0;
  for (std::uint32_t t = c.soluble_first_tile; t < c.soluble_first_tile + c.soluble_tile_count; ++t) {
    largest = std::max(largest, s.tiles3d[t].instance_count);
    for (std::uint32_t m = s.tiles3d[t].first_instance; m < s.tiles3d[t].first_instance + s.tiles3d[t].instance_count; ++m) {
      const double r = s.type_radius[s.instances[m].molecule_type];
      lo = glm::min(lo, dvec3(s.instances[m].position) - r);
      hi = glm::max(hi, dvec3(s.instances[m].position) + r);
    }
  }
  rc.counts.y = largest;
  if (largest > 0) {
    // Rounding of the float placement and of the slab test: a generous hundredth of an Å.
    lo -= 0.01, hi += 0.01;
    if (lo.x < -B || lo.y < -B || lo.z < -B || hi.x > 2 * B || hi.y > 2 * B || hi.z > 2 * B)
      s.fail("compartments[" + std::to_string(ci) + "]",
             "molecules of its Wang cubes reach farther than one box beyond their own; the core renderer "
             "looks one box around each cell");
    rc.reach_lo = glm::vec4(vec3(lo), 0.f);
    rc.reach_hi = glm::vec4(vec3(hi), 0.f);
    rc.span.z = 1;
  }
  rc.core_skip.x = std::uint32_t(s.core_skip_layout.first_cell[ci]);
}

void build_core(SceneState& s) {
  for (std::uint32_t t = 0; t < s.tiles3d.size(); ++t) {
    if (s.tiles3d[t].instance_count == 0) continue;
    std::vector<VkAabbPositionsKHR> boxes;
    for (std::uint32_t m = s.tiles3d[t].first_instance; m < s.tiles3d[t].first_instance + s.tiles3d[t].instance_count; ++m) {
      const dvec3 pos(s.instances[m].position);
      const double e = s.type_radius[s.instances[m].molecule_type] + 0.01;
      boxes.push_back(box_of(pos - e, pos + e));
    }
    s.add_tile_level(s.first_cube + t, boxes);
  }
  const std::vector<std::uint32_t> kept = render::kept_boxes(s, s.type_radius);
  s.section_buffers[gpu::NANO_B_KEPT_BOXES] = s.storage(std::as_bytes(std::span(kept)));
  s.report.memory.derived += s.section_buffers[gpu::NANO_B_KEPT_BOXES].size();
}

void write_core_descriptors(const SceneState& s, VkDescriptorSet set) {
  vk::write_storage_buffer(s.device.handle(), set, gpu::NANO_B_KEPT_BOXES, s.section_buffers[gpu::NANO_B_KEPT_BOXES]);
}

std::optional<VkAabbPositionsKHR> core_grid_box(const SceneState& s, std::uint32_t ci) {
  if (s.render_compartments[ci].span.z == 0) return std::nullopt;
  const gpu::Compartment& c = s.compartments[ci];
  const dvec3 B(c.grid_min.w);
  const dvec3 lo = dvec3(c.grid_min) - B;
  const dvec3 hi = dvec3(c.grid_min) + B * (dvec3(glm::uvec3(c.grid_dims)) + 1.0);
  return outward_box(vec3(lo), vec3(hi));
}

}  // namespace nano::levels
