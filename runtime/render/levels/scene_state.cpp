#include "runtime/render/levels/scene_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "runtime/placement/membrane_distortion.hpp"
#include "runtime/render/morton.hpp"

namespace nano::levels {

VkAabbPositionsKHR box_of(const glm::dvec3& lo, const glm::dvec3& hi) {
  return {float(lo.x), float(lo.y), float(lo.z), float(hi.x), float(hi.y), float(hi.z)};
}

VkAabbPositionsKHR outward_box(const glm::vec3& lo, const glm::vec3& hi) {
  const auto down = [](float v) { return std::nextafter(v, -std::numeric_limits<float>::infinity()); };
  const auto up = [](float v) { return std::nextafter(v, std::numeric_limits<float>::infinity()); };
  return {down(lo.x), down(lo.y), down(lo.z), up(hi.x), up(hi.y), up(hi.z)};
}

SceneState::SceneState(const vk::Device& d, const format::Package& p, const render::SceneOptions& o)
    : PackageView(p), device(d), package(p), options(o), type_radius(atom_bounding_radii()),
      core_skip_layout(format::core_skip_layout(compartments)) {
  if (compartment_instances.size() >= (1u << 24))
    fail("compartment_instances", "more than 2^24 compartment instances (the µLAS custom index has 24 bits)");
  if (core_skip_layout.cells >= (std::uint64_t{1} << 32))
    fail("core_skip", "more than 2^32 cells in the widened core grids (the shader indexes them with 32 bits)");
  first_square = std::uint32_t(molecules.size());
  first_cube = first_square + std::uint32_t(tiles2d.size());
  first_area = first_cube + std::uint32_t(tiles3d.size());
  first_atom_square = first_area + std::uint32_t(compartments.size());
  first_bead = first_atom_square + std::uint32_t(tiles2d.size());
  first_class_square = first_bead + std::uint32_t(molecules.size());
  level_records.assign(first_class_square + (placement::kDistortionClasses - 1) * tiles2d.size(), gpu::RenderLevel{});
  levels.resize(level_records.size());
  render_compartments.assign(compartments.size(), gpu::RenderCompartment{});
}

std::vector<format::InstanceTransform> SceneState::package_transforms() const {
  std::vector<format::InstanceTransform> t;
  for (const gpu::CompartmentInstance& ci : compartment_instances) t.push_back(format::instance_transform(ci));
  return t;
}

void SceneState::fail(const std::string& where, const std::string& rule) const { throw InputError(package.name(), where, rule); }

vk::Buffer SceneState::storage(std::span<const std::byte> bytes) const {
  static const std::byte zeros[16] = {};
  if (bytes.empty()) bytes = std::span(zeros);
  return vk::Buffer::with_data(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceLocal);
}

void SceneState::note_scratch(const vk::AccelerationStructure& s) {
  report.memory.scratch_peak = std::max<std::uint64_t>(report.memory.scratch_peak, s.scratch_size());
}

Level SceneState::build_level(const std::vector<VkAabbPositionsKHR>& boxes, const std::vector<std::uint32_t>& values,
                              std::uint32_t record, std::uint64_t& category, std::uint32_t stride) {
  const std::vector<std::uint32_t> order = render::morton_order(boxes);
  std::vector<VkAabbPositionsKHR> sorted;
  gpu::RenderLevel& rl = level_records[record];
  rl.order_first = std::uint32_t(orders.size());
  rl.count = std::uint32_t(boxes.size());
  for (std::uint32_t i : order) {
    sorted.push_back(boxes[i]);
    for (std::uint32_t k = 0; k < stride; ++k) orders.push_back(values[std::size_t(stride) * i + k]);
  }
  const vk::Buffer input = vk::Buffer::with_data(device, std::as_bytes(std::span(sorted)), vk::kBuildInputUsage,
                                                 vk::MemoryUse::DeviceLocal);
  Level level;
  level.blas = vk::build_bottom_level(device, vk::AabbGeometry{input.address(), std::uint32_t(sorted.size())});
  const VkAccelerationStructureInstanceKHR identity = vk::make_instance(level.blas, glm::dmat4(1.0), 0);
  level.tlas = vk::build_top_level(device, std::span(&identity, 1));
  rl.address = glm::uvec2(std::uint32_t(level.tlas.address()), std::uint32_t(level.tlas.address() >> 32));
  category += level.blas.size() + level.tlas.size();
  note_scratch(level.blas);
  note_scratch(level.tlas);
  return level;
}

void SceneState::add_tile_level(std::uint32_t record, const std::vector<VkAabbPositionsKHR>& boxes) {
  std::vector<std::uint32_t> molecule(boxes.size());
  for (std::uint32_t i = 0; i < molecule.size(); ++i) molecule[i] = i;
  levels[record] = build_level(boxes, molecule, record, report.memory.mlas);
  ++report.mlas_count;
}

}  // namespace nano::levels
