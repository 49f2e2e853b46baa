#include "runtime/render/levels/medium.hpp"

#include <cmath>
#include <span>
#include <vector>

#include "runtime/placement/medium_rule.hpp"
#include "runtime/render/levels/level_table.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"

namespace nano::levels {
namespace {

using glm::dvec3;
using glm::vec3;

// The medium's per-instance records and exclusion structure for these instance transforms; a
// placeholder structure without a medium, so the binding is always valid.
void build_medium_instances(SceneState& s, std::span<const format::InstanceTransform> transforms) {
  std::vector<VkAabbPositionsKHR> boxes;
  if (s.has_medium()) {
    s.medium_records = placement::medium_instances(s, transforms);
    const dvec3 region_min(s.medium[0].region_min);
    for (std::uint32_t i = 0; i < transforms.size(); ++i) {
      const auto [lo, hi] = placement::exclusion_box(s.exclusion_fields[s.compartment_instances[i].compartment], transforms[i], region_min);
      boxes.push_back(box_of(lo, hi));
    }
  }
  if (s.medium_records.empty()) s.medium_records.push_back(gpu::MediumInstance{});  // no buffer may be empty
  if (boxes.empty()) boxes.push_back(box_of(dvec3(-2e30), dvec3(-1e30)));    // never met by a region-space ray
  if (s.medium_instance_buffer.handle() != VK_NULL_HANDLE) s.report.memory.derived -= s.medium_instance_buffer.size();
  if (s.exclusion_tlas.handle() != VK_NULL_HANDLE) s.report.memory.ulas -= s.exclusion_tlas.size() + s.exclusion_blas.size();
  s.medium_instance_buffer = s.storage(std::as_bytes(std::span(s.medium_records)));
  const vk::Buffer input =
      vk::Buffer::with_data(s.device, std::as_bytes(std::span(boxes)), vk::kBuildInputUsage, vk::MemoryUse::DeviceLocal);
  s.exclusion_blas = vk::build_bottom_level(s.device, vk::AabbGeometry{input.address(), std::uint32_t(boxes.size())});
  const VkAccelerationStructureInstanceKHR whole = vk::make_instance(s.exclusion_blas, glm::dmat4(1.0), 0);
  s.exclusion_tlas = vk::build_top_level(s.device, std::span(&whole, 1));
  s.report.memory.derived += s.medium_instance_buffer.size();
  s.report.memory.ulas += s.exclusion_tlas.size() + s.exclusion_blas.size();
  s.render_medium.numbers.z = s.has_medium() ? std::uint32_t(s.compartment_instances.size()) : 0u;
}

}  // namespace

// Its copies are numbered after every compartment instance's (the µLAS row counts them).
void build_medium(SceneState& s) {
  s.render_medium.numbers = glm::uvec4(std::uint32_t(s.medium_number_base), std::uint32_t(s.medium_number_base >> 32), 0u, 0u);
  if (s.has_medium()) {
    // Every medium copy's sphere in its cube's space (the box its DDA looks one box around).
    dvec3 lo(INFINITY), hi(-INFINITY);
    const gpu::Medium& m = s.medium[0];
    for (std::uint32_t t = m.tiles.x; t < m.tiles.x + m.tiles.y; ++t)
      for (std::uint32_t k = s.tiles3d[t].first_instance; k < s.tiles3d[t].first_instance + s.tiles3d[t].instance_count; ++k) {
        const double r = s.type_radius[s.instances[k].molecule_type];
        lo = glm::min(lo, dvec3(s.instances[k].position) - r), hi = glm::max(hi, dvec3(s.instances[k].position) + r);
      }
    if (!(lo.x <= hi.x)) lo = hi = dvec3(0.0);
    s.render_medium.reach_lo = glm::vec4(vec3(lo - 0.01), 0.f);
    s.render_medium.reach_hi = glm::vec4(vec3(hi + 0.01), 0.f);
  }
  build_medium_instances(s, s.package_transforms());
  s.render_medium_buffer = vk::Buffer(s.device, sizeof(gpu::RenderMedium), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
  s.report.memory.derived += s.render_medium_buffer.size();
}

// The eye's region box and its place within (a two-float pair); moved instances move the exclusions.
void set_medium_eye(SceneState& s, const EyeUpdate& u) {
  if (s.has_medium()) {
    if (!u.moved.empty()) build_medium_instances(s, u.moved);
    else if (s.moved_medium) build_medium_instances(s, s.package_transforms());
    s.moved_medium = !u.moved.empty();
    const double B = s.medium[0].region_min.w;
    const dvec3 eye_region = u.eye - dvec3(s.medium[0].region_min);
    const dvec3 box = glm::clamp(glm::floor(eye_region / B), dvec3(-1e9), dvec3(1e9));
    const dvec3 within = eye_region - box * B;
    const vec3 hi(within);
    s.render_medium.eye_box = glm::ivec4(glm::ivec3(box), 0);
    s.render_medium.eye_hi = glm::vec4(hi, 0.f);
    s.render_medium.eye_lo = glm::vec4(vec3(within - dvec3(hi)), 0.f);
  }
  s.render_medium_buffer.write(std::as_bytes(std::span(&s.render_medium, 1)));
}

void write_medium_descriptors(const SceneState& s, VkDescriptorSet set) {
  const VkDevice d = s.device.handle();
  vk::write_storage_buffer(d, set, gpu::NANO_B_MEDIUM_INSTANCES, s.medium_instance_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_RENDER_MEDIUM, s.render_medium_buffer);
  vk::write_acceleration_structure(d, set, gpu::NANO_B_EXCLUSION_TLAS, s.exclusion_tlas);
}

}  // namespace nano::levels
