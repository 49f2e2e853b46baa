#pragma once
// What GpuScene holds on the device, shared by the levels of level_table.hpp: the package's records,
// the records every level writes into (RenderLevel records and their primitive orders, per-compartment
// RenderCompartment records), the load report, and each level's own buffers and structures, grouped
// by the file that builds them. Levels are built in table order and may read what an earlier row
// built (level_table.hpp says which).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "format/core_skip.hpp"
#include "format/package.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/visibility.hpp"
#include "runtime/render/flat_level.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/vk/acceleration_structure.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"
#include "shared/render_scene.h"

namespace nano::levels {

// One level object: a BLAS of AABBs and a TLAS holding it once with the identity transform.
struct Level {
  vk::AccelerationStructure blas, tlas;
};

VkAabbPositionsKHR box_of(const glm::dvec3& lo, const glm::dvec3& hi);
// A float box that contains [lo, hi] after rounding: one ulp outward on every side.
VkAabbPositionsKHR outward_box(const glm::vec3& lo, const glm::vec3& hi);

struct SceneState : format::PackageView {
  // Checks what the renderer needs beyond the validator that every level relies on (instance and
  // core-cell counts) and lays out the level records; builds nothing.
  SceneState(const vk::Device& device, const format::Package& package, const render::SceneOptions& options);

  const vk::Device& device;
  const format::Package& package;
  render::SceneOptions options;
  render::LoadReport report;
  std::vector<double> type_radius;  // from the atoms (as the oracle)
  format::CoreSkipLayout core_skip_layout;
  placement::Visibility visibility;

  // Level records: types, squares, cubes, replication areas, then (2-level only) squares of atoms,
  // beads and the squares of distortion classes after the first (RenderFrame.levels, level_table.hpp).
  std::uint32_t first_square = 0, first_cube = 0, first_area = 0, first_atom_square = 0, first_bead = 0, first_class_square = 0;
  std::vector<gpu::RenderLevel> level_records;
  std::vector<Level> levels;            // one per level record that has primitives
  std::vector<std::uint32_t> orders;    // every level's primitive → what it names, in build order
  std::vector<gpu::RenderCompartment> render_compartments;  // planned by the membrane and core rows
  vk::Buffer level_buffer, order_buffer;

  // sections.cpp: indexed by binding (package sections, and the core's kept boxes); others unused.
  std::vector<vk::Buffer> section_buffers;
  // membrane.cpp: the shell offsets of the chosen mode; per Wang square the tile-space union of its mLAS boxes.
  std::vector<gpu::TriangleShell> shell_records;
  vk::Buffer shell_buffer;
  std::vector<std::pair<glm::dvec3, glm::dvec3>> square_reach;
  bool large_replication_areas = false;  // some compartment's repLAS has more than NANO_DIRECT_SLOTS slots
  // ulas.cpp: per compartment a BLAS (empty handle: nothing to trace), its build input (prisms, then
  // the core box) and their union; the instance TLAS, rebuilt for every eye.
  std::vector<vk::AccelerationStructure> compartment_blas;
  std::vector<std::vector<VkAabbPositionsKHR>> compartment_boxes;
  std::vector<std::pair<glm::dvec3, glm::dvec3>> compartment_bounds;
  std::vector<gpu::RenderInstance> render_instances;  // eyes rewritten by set_eye
  vk::Buffer render_compartment_buffer, render_instance_buffer;
  vk::AccelerationStructure ulas;
  bool has_ulas = false;
  // flat.cpp: the level (empty until a budget asks for copies), what it is chosen for, its triangle
  // bits and the record bound in place of its copies while it is empty.
  std::unique_ptr<render::FlatLevel> flat;
  std::uint64_t flatten_budget = 0;
  gpu::Camera flatten_camera{};
  bool flatten_both_sides = false;
  std::uint64_t flatten_new_copies = ~std::uint64_t{0};
  vk::Buffer flat_placeholder, flat_triangle_buffer;
  // medium.cpp (shared/medium.h): per instance region → compartment records, the exclusion fields as
  // region-space boxes (one BLAS, primitive = instance), and the per-frame record.
  std::vector<gpu::MediumInstance> medium_records;
  vk::Buffer medium_instance_buffer, render_medium_buffer;
  vk::AccelerationStructure exclusion_blas, exclusion_tlas;
  gpu::RenderMedium render_medium{};
  std::uint64_t medium_number_base = 0;  // copy numbers of the medium follow every instance's
  bool moved_medium = false;             // the medium's records follow moved instances (animation)

  bool has_medium() const { return !medium.empty(); }
  std::vector<format::InstanceTransform> package_transforms() const;

  [[noreturn]] void fail(const std::string& where, const std::string& rule) const;
  // A device-local storage buffer of `bytes`; Vulkan has no empty buffers, so an empty span becomes
  // 16 zero bytes nobody indexes.
  vk::Buffer storage(std::span<const std::byte> bytes) const;
  void note_scratch(const vk::AccelerationStructure& s);
  // Builds the level of record `record` from `boxes`, Morton-sorted; orders[order_first + p] =
  // values[i] for the box i that became primitive p. Adds the structures' size to `category`.
  // With stride k, box i names k values values[k·i .. k·i + k) (a 2-level atom tile names a molecule
  // and an atom), stored at orders[order_first + k·p].
  Level build_level(const std::vector<VkAabbPositionsKHR>& boxes, const std::vector<std::uint32_t>& values,
                    std::uint32_t record, std::uint64_t& category, std::uint32_t stride = 1);
  // A Wang square's or cube's mLAS: orders hold the molecule's index within its tile.
  void add_tile_level(std::uint32_t record, const std::vector<VkAabbPositionsKHR>& boxes);
};

}  // namespace nano::levels
