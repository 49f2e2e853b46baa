#include "runtime/render/levels/sections.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <unistd.h>

#include "format/core_skip.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "runtime/vk/error.hpp"
#include "shared/bindings.h"

namespace nano::levels {
namespace {

using format::SectionKind;

// An uncompressed section of a memory-mapped package, through VK_EXT_external_memory_host when
// the device has it: a device that shares host memory (integrated, CPU) reads the mapped pages in
// place; a discrete one copies them to device memory straight from the pages, with no staging
// copy. Anything else (compressed sections, sizes not a multiple of 4 bytes, a range outside the
// mapping, a driver that refuses) returns an empty buffer and takes the staging path.
vk::Buffer try_import(SceneState& s, SectionKind kind, std::span<const std::byte> bytes) {
  const format::SectionEntry* e = s.package.entry(kind);
  if (!s.device.host_import() || !s.package.memory_mapped() || e == nullptr || e->codec != std::uint16_t(format::Codec::none) || bytes.empty() ||
      bytes.size() % 4 != 0)
    return {};
  const auto file = s.package.file_bytes();
  const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE)), align = s.device.host_import_alignment();
  const auto at = [](const std::byte* b) { return reinterpret_cast<std::uintptr_t>(b); };
  const std::uintptr_t first = at(bytes.data()) / align * align;
  const std::uintptr_t last = (at(bytes.data()) + bytes.size() + align - 1) / align * align;
  const std::uintptr_t mapped_end = (at(file.data()) + file.size() + page - 1) / page * page;
  if (first < at(file.data()) || last > mapped_end) return {};
  try {
    vk::Buffer imported = vk::Buffer::import_host(s.device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    if (s.device.report().type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) {
      vk::Buffer copy = vk::Buffer::device_copy(s.device, imported, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
      s.report.memory.package_data += copy.size();
      ++s.report.sections_copied_from_pages;
      return copy;
    }
    s.report.memory.package_imported += bytes.size();
    ++s.report.sections_imported;
    return imported;
  } catch (const vk::VulkanError&) {
    return {};
  }
}

}  // namespace

void build_sections(SceneState& s) {
  const std::pair<std::uint32_t, SectionKind> kinds[] = {
      {gpu::NANO_B_MOLECULES, SectionKind::molecules},       {gpu::NANO_B_ATOMS, SectionKind::atoms},
      {gpu::NANO_B_TILES2D, SectionKind::tiles2d},           {gpu::NANO_B_TILES3D, SectionKind::tiles3d},
      {gpu::NANO_B_INSTANCES, SectionKind::instances},       {gpu::NANO_B_RECIPES, SectionKind::recipes},
      {gpu::NANO_B_RECIPE_INDICES, SectionKind::recipe_indices}, {gpu::NANO_B_MESHES, SectionKind::meshes},
      {gpu::NANO_B_VERTEX_POSITIONS, SectionKind::vertex_positions}, {gpu::NANO_B_VERTEX_NORMALS, SectionKind::vertex_normals},
      {gpu::NANO_B_VERTEX_UVS, SectionKind::vertex_uvs},            {gpu::NANO_B_TRIANGLES, SectionKind::triangles},
      {gpu::NANO_B_COMPARTMENTS, SectionKind::compartments}, {gpu::NANO_B_OCCUPANCY, SectionKind::occupancy},
      {gpu::NANO_B_BOUNDARY_BOXES, SectionKind::boundary_boxes}, {gpu::NANO_B_MASK_WORDS, SectionKind::mask_words},
      {gpu::NANO_B_TRIANGLE_DROPS, SectionKind::triangle_drops}, {gpu::NANO_B_DROPPED_COPIES, SectionKind::dropped_copies},
      {gpu::NANO_B_BEADS, SectionKind::beads},            {gpu::NANO_B_CORE_SKIP, SectionKind::core_skip},
      {gpu::NANO_B_MEDIUM, SectionKind::medium},          {gpu::NANO_B_EXCLUSION_FIELDS, SectionKind::exclusion_fields},
      {gpu::NANO_B_EXCLUSION_VALUES, SectionKind::exclusion_values},
  };
  s.section_buffers.resize(gpu::NANO_SCENE_BINDING_COUNT);
  for (const auto& [binding, kind] : kinds) {
    std::span<const std::byte> bytes = s.package.raw_bytes(kind);
    if (kind == SectionKind::triangle_drops && s.triangle_drops.empty()) {
      // No drops (a package before 2.2, or nothing dropped): one zero range per triangle, so the
      // shader reads every triangle's range without asking whether the section exists.
      const std::vector<gpu::TriangleDrops> none(std::max<std::size_t>(s.triangles.size(), 1));
      s.section_buffers[binding] = s.storage(std::as_bytes(std::span(none)));
      s.report.memory.derived += s.section_buffers[binding].size();
      continue;
    }
    std::vector<std::uint8_t> derived;
    if (kind == SectionKind::core_skip && bytes.empty() && s.core_skip_layout.cells > 0) {
      // A package before 2.7: the same levels the baker would have written.
      derived = format::core_skip_section({s.compartments, s.occupancy, s.tiles3d, s.recipes, s.recipe_indices, s.boundary_boxes, s.mask_words});
      bytes = std::as_bytes(std::span(derived));
    }
    if (vk::Buffer imported = try_import(s, kind, bytes); imported.handle() != VK_NULL_HANDLE) {
      s.section_buffers[binding] = std::move(imported);
      continue;
    }
    std::vector<std::byte> padded;
    if (bytes.size() % 4 != 0) {  // the shader reads occupancy bytes as 32-bit words
      padded.assign(bytes.begin(), bytes.end());
      padded.resize((bytes.size() + 3) / 4 * 4, std::byte{0});
      bytes = padded;
    }
    s.section_buffers[binding] = s.storage(bytes);
    s.report.memory.package_data += s.section_buffers[binding].size();
  }
}

void write_section_descriptors(const SceneState& s, VkDescriptorSet set) {
  const VkDevice d = s.device.handle();
  for (std::uint32_t b = gpu::NANO_B_MOLECULES; b <= gpu::NANO_B_MASK_WORDS; ++b) {
    if (b == gpu::NANO_B_TRIANGLE_SHELLS) continue;  // the membrane's: offsets of the shell mode
    vk::write_storage_buffer(d, set, b, s.section_buffers[b]);
  }
  for (std::uint32_t b : {gpu::NANO_B_TRIANGLE_DROPS, gpu::NANO_B_DROPPED_COPIES, gpu::NANO_B_BEADS, gpu::NANO_B_CORE_SKIP,
                         gpu::NANO_B_MEDIUM, gpu::NANO_B_EXCLUSION_FIELDS, gpu::NANO_B_EXCLUSION_VALUES})
    vk::write_storage_buffer(d, set, b, s.section_buffers[b]);
}

}  // namespace nano::levels
