#include "runtime/render/gpu_scene.hpp"

#include <chrono>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/render/levels/level_table.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"

namespace nano::render {
namespace {

using glm::dvec3;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ShellMode parse_shell_mode(std::string_view text, const InputSource& source) {
  for (ShellMode m : {ShellMode::adaptive_overlap, ShellMode::adaptive, ShellMode::fixed_overlap, ShellMode::fixed})
    if (text == to_string(m)) return m;
  source.fail("shell mode '" + std::string(text) + "' is not one of adaptive-overlap, adaptive, fixed-overlap, fixed");
}

const char* to_string(ShellMode mode) {
  switch (mode) {
    case ShellMode::adaptive_overlap: return "adaptive-overlap";
    case ShellMode::adaptive: return "adaptive";
    case ShellMode::fixed_overlap: return "fixed-overlap";
    case ShellMode::fixed: return "fixed";
  }
  return "?";
}

nlohmann::json to_json(const LoadReport& r) {
  return {{"seconds", {{"upload", r.upload_seconds}, {"nlas", r.nlas_seconds}, {"mlas", r.mlas_seconds}, {"ulas", r.ulas_seconds}}},
          {"device_memory_bytes", r.memory.total()},
          {"device_memory",
           {{"package_data", r.memory.package_data},
            {"package_imported", r.memory.package_imported},
            {"derived", r.memory.derived},
            {"nlas", r.memory.nlas},
            {"mlas", r.memory.mlas},
            {"ulas", r.memory.ulas},
            {"flat", r.memory.flat},
            {"scratch_peak", r.memory.scratch_peak}}},
          {"structures", {{"nlas", r.nlas_count}, {"mlas", r.mlas_count}, {"prisms", r.prisms}}},
          {"flat_level",
           {{"copies", r.flattened_copies}, {"triangles", r.flattened_triangles}, {"last_build_seconds", r.flat_seconds}}},
          {"sections", {{"imported", r.sections_imported}, {"copied_from_pages", r.sections_copied_from_pages}}}};
}

// The scene's state and the level table's walk over it: plan, build, eye, descriptors.
struct GpuScene::Impl : levels::SceneState {
  Impl(const vk::Device& d, const format::Package& package, const SceneOptions& o) : SceneState(d, package, o) {
    auto start = std::chrono::steady_clock::now();
    for (std::uint32_t ci = 0; ci < compartments.size(); ++ci)
      for (const levels::LevelEntry& level : levels::level_table())
        if (level.plan) level.plan(*this, ci);
    report.upload_seconds += seconds_since(start);
    for (const levels::LevelEntry& level : levels::level_table()) {
      start = std::chrono::steady_clock::now();
      level.build(*this);
      report.*level.seconds += seconds_since(start);
    }
    // The records every level wrote into, after the last build.
    level_buffer = storage(std::as_bytes(std::span(level_records)));
    order_buffer = storage(std::as_bytes(std::span(orders)));
    report.memory.derived += level_buffer.size() + order_buffer.size();
  }

  void set_eye(const dvec3& eye, std::span<const format::InstanceTransform> moved) {
    if (!moved.empty() && moved.size() != compartment_instances.size())
      throw std::invalid_argument("set_eye: " + std::to_string(moved.size()) + " transforms for " +
                                  std::to_string(compartment_instances.size()) + " compartment instances");
    for (const levels::LevelEntry& level : levels::level_table())
      if (level.set_eye) level.set_eye(*this, {eye, moved});
  }

  void set_visibility(const placement::Visibility& v) {
    if (v == visibility) return;
    visibility = v;
    std::vector<gpu::RenderLevel> shown = level_records;
    for (std::uint32_t t = 0; t < molecules.size(); ++t)
      if (v.molecule_type_hidden(t)) shown[t].count = shown[first_bead + t].count = 0;
    report.memory.derived -= level_buffer.size();
    level_buffer = storage(std::as_bytes(std::span(shown)));
    report.memory.derived += level_buffer.size();
  }
};

GpuScene::GpuScene(const vk::Device& device, const format::Package& package, const SceneOptions& options)
    : impl_(std::make_unique<Impl>(device, package, options)) {}
GpuScene::~GpuScene() = default;
GpuScene::GpuScene(GpuScene&&) noexcept = default;

void GpuScene::set_eye(const glm::dvec3& eye) { impl_->set_eye(eye, {}); }
void GpuScene::set_eye(const glm::dvec3& eye, std::span<const format::InstanceTransform> transforms) {
  impl_->set_eye(eye, transforms);
}
const format::Package& GpuScene::package() const { return impl_->package; }

void GpuScene::write_descriptors(VkDescriptorSet set) const {
  const Impl& s = *impl_;
  if (!s.has_ulas) throw std::logic_error("GpuScene::write_descriptors before set_eye");
  for (const levels::LevelEntry& level : levels::level_table())
    if (level.write_descriptors) level.write_descriptors(s, set);
  vk::write_storage_buffer(s.device.handle(), set, gpu::NANO_B_LEVELS, s.level_buffer);
  vk::write_storage_buffer(s.device.handle(), set, gpu::NANO_B_ORDERS, s.order_buffer);
}

void GpuScene::set_visibility(const placement::Visibility& visibility) { impl_->set_visibility(visibility); }

void GpuScene::set_flatten(std::uint64_t bytes, const gpu::Camera& camera, bool both_sides, std::uint64_t new_copies) {
  impl_->flatten_new_copies = new_copies;
  impl_->flatten_budget = bytes;
  impl_->flatten_camera = camera;
  impl_->flatten_both_sides = both_sides;
}

glm::vec4 GpuScene::flat_eye(const glm::dvec3& eye) const {
  const Impl& s = *impl_;
  if (s.flat->empty()) return glm::vec4(0.f);
  return glm::vec4(glm::vec3(eye - s.flat->anchor()), 1.f);
}

std::uint32_t GpuScene::first_square_level() const { return impl_->first_square; }
std::uint32_t GpuScene::first_cube_level() const { return impl_->first_cube; }
std::uint32_t GpuScene::first_atom_square_level() const { return impl_->first_atom_square; }
std::uint32_t GpuScene::first_bead_level() const { return impl_->first_bead; }
bool GpuScene::has_beads() const { return !impl_->bead_ranges.empty(); }
bool GpuScene::has_medium() const { return impl_->has_medium(); }
bool GpuScene::has_large_replication_areas() const { return impl_->large_replication_areas; }
std::uint32_t GpuScene::molecule_type_count() const { return std::uint32_t(impl_->molecules.size()); }
const LoadReport& GpuScene::report() const { return impl_->report; }

}  // namespace nano::render
