#include "runtime/render/levels/ulas.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include <glm/gtc/matrix_access.hpp>

#include "runtime/render/levels/core.hpp"
#include "runtime/render/levels/level_table.hpp"
#include "runtime/render/levels/membrane.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/render/morton.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"

namespace nano::levels {
namespace {

using glm::dvec3;
using glm::vec3;

// Compartment ci's BLAS input: its prisms in Morton order (their triangles appended to orders,
// RenderCompartment.counts.z/w), then its core grid's box.
std::vector<VkAabbPositionsKHR> compartment_input(SceneState& s, std::uint32_t ci) {
  gpu::RenderCompartment& rc = s.render_compartments[ci];
  std::vector<VkAabbPositionsKHR> prisms;
  std::vector<std::uint32_t> prism_triangles;
  membrane_prisms(s, ci, prisms, prism_triangles);
  const std::vector<std::uint32_t> order = render::morton_order(prisms);
  std::vector<VkAabbPositionsKHR> boxes;
  rc.counts.z = std::uint32_t(prisms.size());
  rc.counts.w = std::uint32_t(s.orders.size());
  for (std::uint32_t i : order) {
    boxes.push_back(prisms[i]);
    s.orders.push_back(prism_triangles[i]);
  }
  if (const std::optional<VkAabbPositionsKHR> grid = core_grid_box(s, ci)) boxes.push_back(*grid);
  s.report.prisms += prisms.size();
  return boxes;
}

// Every instance's RenderInstance with its copy numbers' base (the medium's copies follow them all).
void build_render_instances(SceneState& s) {
  std::uint64_t base = 0;
  for (std::uint32_t i = 0; i < s.compartment_instances.size(); ++i) {
    const gpu::CompartmentInstance& ci = s.compartment_instances[i];
    s.render_instances.push_back(
        {glm::uvec4(std::uint32_t(base), std::uint32_t(base >> 32), ci.compartment, s.flat->first_bit(i)), {}, {}, {}});
    const gpu::RenderCompartment& rc = s.render_compartments[ci.compartment];
    const gpu::Compartment& c = s.compartments[ci.compartment];
    const std::uint64_t core_span =
        rc.span.z ? std::uint64_t{c.grid_dims.x} * c.grid_dims.y * c.grid_dims.z * rc.counts.y : 0;
    base += (std::uint64_t{rc.span.y} << 32 | rc.span.x) + core_span;
  }
  s.medium_number_base = base;
  s.render_instance_buffer = vk::Buffer(s.device, s.render_instances.size() * sizeof(gpu::RenderInstance),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
}

// Instance i's TLAS record for transform t (camera-relative: translation − eye), its RenderInstance
// eye, and its box in world space for the build order.
VkAccelerationStructureInstanceKHR instance_record(SceneState& s, std::uint32_t i, const format::InstanceTransform& t,
                                                   const dvec3& eye, VkAabbPositionsKHR& world_box) {
  const gpu::CompartmentInstance& ci = s.compartment_instances[i];
  if (!(std::abs(glm::determinant(t.linear)) > 1e-12)) throw std::invalid_argument("set_eye: singular instance transform");
  glm::dmat4 m(t.linear);
  m[3] = glm::dvec4(t.translation - eye, 1.0);
  // The eye in compartment space, L⁻¹(eye − T), in double, split into two floats; L⁻¹ by rows.
  const glm::dmat3 from_world = glm::inverse(glm::dmat3(m));
  const dvec3 eye_c = from_world * -dvec3(m[3]);
  const vec3 hi(eye_c);
  s.render_instances[i].eye_hi = glm::vec4(hi, 0.f);
  s.render_instances[i].eye_lo = glm::vec4(vec3(eye_c - dvec3(hi)), 0.f);
  for (int r = 0; r < 3; ++r) s.render_instances[i].from_world[r] = glm::vec4(vec3(glm::row(from_world, r)), 0.f);
  const std::uint8_t mask = s.visibility.compartment_hidden(ci.compartment) ? 0x00 : 0xFF;  // rays query with 0xFF
  const auto& [lo, hi_c] = s.compartment_bounds[ci.compartment];
  dvec3 w_lo(INFINITY), w_hi(-INFINITY);
  for (int corner = 0; corner < 8; ++corner) {
    const dvec3 p((corner & 1) ? hi_c.x : lo.x, (corner & 2) ? hi_c.y : lo.y, (corner & 4) ? hi_c.z : lo.z);
    const dvec3 w = dvec3(m * glm::dvec4(p, 1.0));
    w_lo = glm::min(w_lo, w), w_hi = glm::max(w_hi, w);
  }
  world_box = box_of(w_lo, w_hi);
  return vk::make_instance(s.compartment_blas[ci.compartment], m, i, mask);
}

}  // namespace

void build_compartment_blas(SceneState& s, std::uint32_t ci, const std::vector<VkAabbPositionsKHR>& boxes) {
  if (s.compartment_blas[ci].handle() != VK_NULL_HANDLE) s.report.memory.ulas -= s.compartment_blas[ci].size();
  s.compartment_blas[ci] = {};
  if (boxes.empty()) return;
  const vk::Buffer input =
      vk::Buffer::with_data(s.device, std::as_bytes(std::span(boxes)), vk::kBuildInputUsage, vk::MemoryUse::DeviceLocal);
  s.compartment_blas[ci] = vk::build_bottom_level(s.device, vk::AabbGeometry{input.address(), std::uint32_t(boxes.size())});
  s.report.memory.ulas += s.compartment_blas[ci].size();
  s.note_scratch(s.compartment_blas[ci]);
}

// Per compartment its prisms and core box as one BLAS; the TLAS waits for the first eye.
void build_ulas(SceneState& s) {
  s.compartment_blas.resize(s.compartments.size());
  for (std::uint32_t ci = 0; ci < s.compartments.size(); ++ci) {
    std::vector<VkAabbPositionsKHR> boxes = compartment_input(s, ci);
    dvec3 lo(INFINITY), hi(-INFINITY);
    for (const VkAabbPositionsKHR& b : boxes)
      lo = glm::min(lo, dvec3(b.minX, b.minY, b.minZ)), hi = glm::max(hi, dvec3(b.maxX, b.maxY, b.maxZ));
    s.compartment_bounds.push_back({lo, hi});
    s.compartment_boxes.push_back(std::move(boxes));
    build_compartment_blas(s, ci, s.compartment_boxes.back());
  }
  s.render_compartment_buffer = s.storage(std::as_bytes(std::span(s.render_compartments)));
  build_render_instances(s);
  s.report.memory.derived += s.render_compartment_buffer.size() + s.render_instance_buffer.size();
}

void set_ulas_eye(SceneState& s, const EyeUpdate& u) {
  std::vector<VkAccelerationStructureInstanceKHR> unsorted;
  std::vector<VkAabbPositionsKHR> world_boxes;  // each instance's box, for the build order
  for (std::uint32_t i = 0; i < s.compartment_instances.size(); ++i) {
    const gpu::CompartmentInstance& ci = s.compartment_instances[i];
    if (s.compartment_blas[ci.compartment].handle() == VK_NULL_HANDLE) continue;
    const format::InstanceTransform t = u.moved.empty() ? format::instance_transform(ci) : u.moved[i];
    unsorted.push_back(instance_record(s, i, t, u.eye, world_boxes.emplace_back()));
  }
  if (s.has_ulas) s.report.memory.ulas -= s.ulas.size();
  s.has_ulas = !unsorted.empty();
  if (!s.has_ulas) s.fail("compartment_instances", "the package places nothing to render");
  // Morton order, as every other build here: lavapipe splits in input order, and a thousand cells
  // in the order the baker placed them made a µLAS whose nodes overlap (1000 cells: frames 2.2×
  // one cell's with the same candidates per pixel). The custom index keeps naming the instance.
  std::vector<VkAccelerationStructureInstanceKHR> records;
  records.reserve(unsorted.size());
  for (const std::uint32_t k : render::morton_order(world_boxes)) records.push_back(unsorted[k]);
  s.ulas = vk::build_top_level(s.device, std::span(records));
  s.note_scratch(s.ulas);
  s.render_instance_buffer.write(std::as_bytes(std::span(s.render_instances)));
  s.report.memory.ulas += s.ulas.size();
}

void write_ulas_descriptors(const SceneState& s, VkDescriptorSet set) {
  const VkDevice d = s.device.handle();
  vk::write_acceleration_structure(d, set, gpu::NANO_B_ULAS, s.ulas);
  vk::write_storage_buffer(d, set, gpu::NANO_B_RENDER_COMPARTMENTS, s.render_compartment_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_RENDER_INSTANCES, s.render_instance_buffer);
}

}  // namespace nano::levels
