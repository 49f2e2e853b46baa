#include "runtime/render/gpu_scene.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include <unistd.h>

#include <glm/gtc/matrix_access.hpp>

#include "common/error.hpp"
#include "format/core_skip.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/medium_rule.hpp"
#include "runtime/placement/membrane_distortion.hpp"
#include "runtime/render/flat_level.hpp"
#include "runtime/render/kept_boxes.hpp"
#include "runtime/render/morton.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "runtime/vk/error.hpp"
#include "shared/bindings.h"
#include "shared/ownership.h"
#include "shared/quaternion.h"
#include "shared/render_scene.h"
#include "shared/shell_prism.h"
#include "shared/tile_mapper.h"

namespace nano::render {
namespace {

using format::SectionKind;
using glm::dmat3;
using glm::dvec2;
using glm::dvec3;
using glm::vec3;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VkAabbPositionsKHR box_of(const dvec3& lo, const dvec3& hi) {
  return {float(lo.x), float(lo.y), float(lo.z), float(hi.x), float(hi.y), float(hi.z)};
}

// A float box that contains [lo, hi] after rounding: one ulp outward on every side.
VkAabbPositionsKHR outward_box(const vec3& lo, const vec3& hi) {
  const auto down = [](float v) { return std::nextafter(v, -std::numeric_limits<float>::infinity()); };
  const auto up = [](float v) { return std::nextafter(v, std::numeric_limits<float>::infinity()); };
  return {down(lo.x), down(lo.y), down(lo.z), up(hi.x), up(hi.y), up(hi.z)};
}

// The binding list of render.comp, in order; scene bindings first.

}  // namespace

ShellMode parse_shell_mode(std::string_view text) {
  for (ShellMode m : {ShellMode::adaptive_overlap, ShellMode::adaptive, ShellMode::fixed_overlap, ShellMode::fixed})
    if (text == to_string(m)) return m;
  throw std::invalid_argument("shell mode '" + std::string(text) +
                              "' is not one of adaptive-overlap, adaptive, fixed-overlap, fixed");
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

// One level object: a BLAS of AABBs and a TLAS holding it once with the identity transform.
struct Level {
  vk::AccelerationStructure blas, tlas;
};

struct GpuScene::Impl : format::PackageView {
  const vk::Device& device;
  const format::Package& p;
  SceneOptions options;
  LoadReport report;

  std::vector<vk::Buffer> section_buffers;  // indexed by Binding (package sections), others unused
  vk::Buffer shell_buffer, render_compartment_buffer, render_instance_buffer, level_buffer, order_buffer;

  std::vector<double> type_radius;                   // from the atoms (as the oracle)
  std::vector<gpu::RenderCompartment> render_compartments;
  std::vector<gpu::RenderInstance> render_instances;  // eyes rewritten by set_eye
  std::vector<gpu::RenderLevel> level_records;
  std::vector<std::uint32_t> orders;
  std::vector<Level> levels;                          // one per level record that has primitives
  std::vector<vk::AccelerationStructure> compartment_blas;  // per compartment; empty handle: nothing to trace
  std::vector<std::vector<VkAabbPositionsKHR>> compartment_boxes;  // their build input (prisms, then the core box)
  std::vector<std::pair<dvec3, dvec3>> compartment_bounds;         // the union of each one's boxes
  vk::AccelerationStructure ulas;
  bool has_ulas = false;
  bool large_replication_areas = false;  // some compartment's repLAS has more than NANO_DIRECT_SLOTS slots
  std::uint64_t flatten_budget = 0;
  gpu::Camera flatten_camera{};
  bool flatten_both_sides = false;
  std::uint64_t flatten_new_copies = ~std::uint64_t{0};
  std::unique_ptr<FlatLevel> flat;       // empty until a budget asks for copies
  vk::Buffer flat_placeholder;           // bound in place of the flat level's records while it is empty
  vk::Buffer flat_triangle_buffer;       // FlatLevel::triangle_bits, rewritten by set_eye
  // Level records: types, squares, cubes, replication areas, then (2-level only) squares of atoms.
  std::uint32_t first_square = 0, first_cube = 0, first_area = 0, first_atom_square = 0, first_bead = 0, first_class_square = 0;
  std::vector<std::pair<dvec3, dvec3>> square_reach;  // per Wang square: tile-space union of its mLAS boxes
  format::CoreSkipLayout core_skip_layout = format::core_skip_layout(compartments);
  // The medium (shared/medium.h): per instance region → compartment records, the exclusion fields
  // as region-space boxes (one BLAS, primitive = instance), and the per-frame record.
  std::vector<gpu::MediumInstance> medium_records;
  vk::Buffer medium_instance_buffer, render_medium_buffer;
  vk::AccelerationStructure exclusion_blas, exclusion_tlas;
  gpu::RenderMedium render_medium{};
  std::uint64_t medium_number_base = 0;  // copy numbers of the medium follow every instance's

  Impl(const vk::Device& d, const format::Package& package, const SceneOptions& o)
      : PackageView(package), device(d), p(package), options(o), type_radius(atom_bounding_radii()) {
    if (compartment_instances.size() >= (1u << 24))
      fail("compartment_instances", "more than 2^24 compartment instances (the µLAS custom index has 24 bits)");
    if (core_skip_layout.cells >= (std::uint64_t{1} << 32))
      fail("core_skip", "more than 2^32 cells in the widened core grids (the shader indexes them with 32 bits)");
    auto start = std::chrono::steady_clock::now();
    upload_sections();
    plan_compartments();
    report.upload_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    first_square = std::uint32_t(molecules.size());
    first_cube = first_square + std::uint32_t(tiles2d.size());
    first_area = first_cube + std::uint32_t(tiles3d.size());
    first_atom_square = first_area + std::uint32_t(compartments.size());
    first_bead = first_atom_square + std::uint32_t(tiles2d.size());
    first_class_square = first_bead + std::uint32_t(molecules.size());
    level_records.assign(first_class_square + (placement::kDistortionClasses - 1) * tiles2d.size(), gpu::RenderLevel{});
    levels.resize(level_records.size());
    build_molecule_levels();
    build_bead_levels();
    report.nlas_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    build_tile_levels();
    build_kept_boxes();
    report.mlas_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    build_compartment_blases();
    upload_derived();
    prepare_medium();
    report.ulas_seconds = seconds_since(start);
  }

  bool has_medium() const { return !medium.empty(); }

  std::vector<format::InstanceTransform> package_transforms() const {
    std::vector<format::InstanceTransform> t;
    for (const gpu::CompartmentInstance& ci : compartment_instances) t.push_back(format::instance_transform(ci));
    return t;
  }

  // The medium's per-instance records and exclusion structure for these instance transforms; a
  // placeholder structure without a medium, so the binding is always valid.
  void build_medium_instances(std::span<const format::InstanceTransform> transforms) {
    std::vector<VkAabbPositionsKHR> boxes;
    if (has_medium()) {
      medium_records = placement::medium_instances(*this, transforms);
      const dvec3 region_min(medium[0].region_min);
      for (std::uint32_t i = 0; i < transforms.size(); ++i) {
        const auto [lo, hi] = placement::exclusion_box(exclusion_fields[compartment_instances[i].compartment], transforms[i], region_min);
        boxes.push_back(box_of(lo, hi));
      }
    }
    if (medium_records.empty()) medium_records.push_back(gpu::MediumInstance{});  // no buffer may be empty
    if (boxes.empty()) boxes.push_back(box_of(dvec3(-2e30), dvec3(-1e30)));    // never met by a region-space ray
    if (medium_instance_buffer.handle() != VK_NULL_HANDLE) report.memory.derived -= medium_instance_buffer.size();
    if (exclusion_tlas.handle() != VK_NULL_HANDLE) report.memory.ulas -= exclusion_tlas.size() + exclusion_blas.size();
    medium_instance_buffer = storage(std::as_bytes(std::span(medium_records)));
    const vk::Buffer input =
        vk::Buffer::with_data(device, std::as_bytes(std::span(boxes)), vk::kBuildInputUsage, vk::MemoryUse::DeviceLocal);
    exclusion_blas = vk::build_bottom_level(device, vk::AabbGeometry{input.address(), std::uint32_t(boxes.size())});
    const VkAccelerationStructureInstanceKHR whole = vk::make_instance(exclusion_blas, glm::dmat4(1.0), 0);
    exclusion_tlas = vk::build_top_level(device, std::span(&whole, 1));
    report.memory.derived += medium_instance_buffer.size();
    report.memory.ulas += exclusion_tlas.size() + exclusion_blas.size();
    render_medium.numbers.z = has_medium() ? std::uint32_t(compartment_instances.size()) : 0u;
  }

  void prepare_medium() {
    render_medium.numbers = glm::uvec4(std::uint32_t(medium_number_base), std::uint32_t(medium_number_base >> 32), 0u, 0u);
    if (has_medium()) {
      // Every medium copy's sphere in its cube's space (the box its DDA looks one box around).
      dvec3 lo(INFINITY), hi(-INFINITY);
      const gpu::Medium& m = medium[0];
      for (std::uint32_t t = m.tiles.x; t < m.tiles.x + m.tiles.y; ++t)
        for (std::uint32_t k = tiles3d[t].first_instance; k < tiles3d[t].first_instance + tiles3d[t].instance_count; ++k) {
          const double r = type_radius[instances[k].molecule_type];
          lo = glm::min(lo, dvec3(instances[k].position) - r), hi = glm::max(hi, dvec3(instances[k].position) + r);
        }
      if (!(lo.x <= hi.x)) lo = hi = dvec3(0.0);
      render_medium.reach_lo = glm::vec4(vec3(lo - 0.01), 0.f);
      render_medium.reach_hi = glm::vec4(vec3(hi + 0.01), 0.f);
    }
    build_medium_instances(package_transforms());
    render_medium_buffer = vk::Buffer(device, sizeof(gpu::RenderMedium), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
    report.memory.derived += render_medium_buffer.size();
  }

  [[noreturn]] void fail(const std::string& where, const std::string& rule) const { throw InputError(p.name(), where, rule); }

  vk::Buffer storage(std::span<const std::byte> bytes) {
    // Vulkan has no empty buffers; an absent section becomes 16 zero bytes nobody indexes.
    static const std::byte zeros[16] = {};
    if (bytes.empty()) bytes = std::span(zeros);
    return vk::Buffer::with_data(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceLocal);
  }

  void upload_sections() {
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
    section_buffers.resize(gpu::NANO_SCENE_BINDING_COUNT);
    for (const auto& [binding, kind] : kinds) {
      std::span<const std::byte> bytes = p.raw_bytes(kind);
      if (kind == SectionKind::triangle_drops && triangle_drops.empty()) {
        // No drops (a package before 2.2, or nothing dropped): one zero range per triangle, so the
        // shader reads every triangle's range without asking whether the section exists.
        const std::vector<gpu::TriangleDrops> none(std::max<std::size_t>(triangles.size(), 1));
        section_buffers[binding] = storage(std::as_bytes(std::span(none)));
        report.memory.derived += section_buffers[binding].size();
        continue;
      }
      std::vector<std::uint8_t> derived;
      if (kind == SectionKind::core_skip && bytes.empty() && core_skip_layout.cells > 0) {
        // A package before 2.7: the same levels the baker would have written.
        derived = format::core_skip_section({compartments, occupancy, tiles3d, recipes, recipe_indices, boundary_boxes, mask_words});
        bytes = std::as_bytes(std::span(derived));
      }
      if (vk::Buffer imported = try_import(kind, bytes); imported.handle() != VK_NULL_HANDLE) {
        section_buffers[binding] = std::move(imported);
        continue;
      }
      std::vector<std::byte> padded;
      if (bytes.size() % 4 != 0) {  // the shader reads occupancy bytes as 32-bit words
        padded.assign(bytes.begin(), bytes.end());
        padded.resize((bytes.size() + 3) / 4 * 4, std::byte{0});
        bytes = padded;
      }
      section_buffers[binding] = storage(bytes);
      report.memory.package_data += section_buffers[binding].size();
    }
  }

  // An uncompressed section of a memory-mapped package, through VK_EXT_external_memory_host when
  // the device has it: a device that shares host memory (integrated, CPU) reads the mapped pages in
  // place; a discrete one copies them to device memory straight from the pages, with no staging
  // copy. Anything else (compressed sections, sizes not a multiple of 4 bytes, a range outside the
  // mapping, a driver that refuses) returns an empty buffer and takes the staging path.
  vk::Buffer try_import(SectionKind kind, std::span<const std::byte> bytes) {
    const format::SectionEntry* e = p.entry(kind);
    if (!device.host_import() || !p.memory_mapped() || e == nullptr || e->codec != std::uint16_t(format::Codec::none) || bytes.empty() ||
        bytes.size() % 4 != 0)
      return {};
    const auto file = p.file_bytes();
    const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE)), align = device.host_import_alignment();
    const auto at = [](const std::byte* b) { return reinterpret_cast<std::uintptr_t>(b); };
    const std::uintptr_t first = at(bytes.data()) / align * align;
    const std::uintptr_t last = (at(bytes.data()) + bytes.size() + align - 1) / align * align;
    const std::uintptr_t mapped_end = (at(file.data()) + file.size() + page - 1) / page * page;
    if (first < at(file.data()) || last > mapped_end) return {};
    try {
      vk::Buffer imported = vk::Buffer::import_host(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
      if (device.report().type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) {
        vk::Buffer copy = vk::Buffer::device_copy(device, imported, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        report.memory.package_data += copy.size();
        ++report.sections_copied_from_pages;
        return copy;
      }
      report.memory.package_imported += bytes.size();
      ++report.sections_imported;
      return imported;
    } catch (const vk::VulkanError&) {
      return {};
    }
  }

  // The molecule-space bounds, copy-number spans and cube reach of every compartment.
  void plan_compartments() {
    for (std::uint32_t ci = 0; ci < compartments.size(); ++ci) {
      const gpu::Compartment& c = compartments[ci];
      const std::string where = "compartments[" + std::to_string(ci) + "]";
      gpu::RenderCompartment rc{};
      if (c.membrane_recipe != gpu::NANO_NO_INDEX) {
        if (triangle_shells.empty()) fail(where, "has a membrane but the package has no triangle_shells: the shell renderer needs its prisms");
        const float S = c.scales.y;
        const float s = S / c.scales.x;
        rc.membrane.x = s;
        rc.membrane.y = s / S;
        rc.membrane.z = 0.5f * S;  // the tile point its lift plane is taken at (chart_smooth_lift_plane)
        std::uint32_t largest = 0;
        for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t)
          largest = std::max(largest, tiles2d[t].instance_count);
        rc.counts.x = largest;
        const std::uint64_t span =
            std::uint64_t{meshes[c.mesh].triangle_count} * c.replication_width * c.replication_height * largest;
        rc.span.x = std::uint32_t(span), rc.span.y = std::uint32_t(span >> 32);
      }
      if (c.soluble_recipe != gpu::NANO_NO_INDEX) {
        const double B = c.grid_min.w;
        dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
        std::uint32_t largest = 0;
        for (std::uint32_t t = c.soluble_first_tile; t < c.soluble_first_tile + c.soluble_tile_count; ++t) {
          largest = std::max(largest, tiles3d[t].instance_count);
          for (std::uint32_t m = tiles3d[t].first_instance; m < tiles3d[t].first_instance + tiles3d[t].instance_count; ++m) {
            const double r = type_radius[instances[m].molecule_type];
            lo = glm::min(lo, dvec3(instances[m].position) - r);
            hi = glm::max(hi, dvec3(instances[m].position) + r);
          }
        }
        rc.counts.y = largest;
        if (largest > 0) {
          // Rounding of the float placement and of the slab test: a generous hundredth of an Å.
          lo -= 0.01, hi += 0.01;
          if (lo.x < -B || lo.y < -B || lo.z < -B || hi.x > 2 * B || hi.y > 2 * B || hi.z > 2 * B)
            fail(where, "molecules of its Wang cubes reach farther than one box beyond their own; the core renderer "
                        "looks one box around each cell");
          rc.reach_lo = glm::vec4(vec3(lo), 0.f);
          rc.reach_hi = glm::vec4(vec3(hi), 0.f);
          rc.span.z = 1;
        }
        rc.core_skip.x = std::uint32_t(core_skip_layout.first_cell[ci]);
      }
      render_compartments.push_back(rc);
    }
  }

  void note_scratch(const vk::AccelerationStructure& s) {
    report.memory.scratch_peak = std::max<std::uint64_t>(report.memory.scratch_peak, s.scratch_size());
  }

  // Builds the level of record `record` from `boxes`, Morton-sorted; orders[order_first + p] =
  // values[i] for the box i that became primitive p. Adds the structures' size to `category`.
  // With stride k, box i names k values values[k·i .. k·i + k) (a 2-level atom tile names a molecule
  // and an atom), stored at orders[order_first + k·p].
  Level build_level(const std::vector<VkAabbPositionsKHR>& boxes, const std::vector<std::uint32_t>& values,
                    std::uint32_t record, std::uint64_t& category, std::uint32_t stride = 1) {
    const std::vector<std::uint32_t> order = morton_order(boxes);
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

  // nLAS: atom boxes in molecule space; orders hold absolute atom indices.
  void build_molecule_levels() {
    for (std::uint32_t t = 0; t < molecules.size(); ++t) {
      const gpu::MoleculeType& m = molecules[t];
      if (m.atom_count == 0) continue;
      std::vector<VkAabbPositionsKHR> boxes;
      std::vector<std::uint32_t> atom_indices;
      for (std::uint32_t a = m.first_atom; a < m.first_atom + m.atom_count; ++a) {
        const dvec3 c(atoms[a].centre_radius);
        const double r = atoms[a].centre_radius.w + 1e-3;  // the exact sphere test decides
        boxes.push_back(box_of(c - r, c + r));
        atom_indices.push_back(a);
      }
      levels[t] = build_level(boxes, atom_indices, t, report.memory.nlas);
      ++report.nlas_count;
    }
  }

  // The level of detail: per molecule type a level over the beads the baker stored for it
  // (sections beads / bead_ranges, validated: indices in range, every type has beads). A package
  // without them (format < 2.5) has no bead levels, and has_beads() says so.
  void build_bead_levels() {
    if (bead_ranges.empty()) return;
    for (std::uint32_t t = 0; t < molecules.size(); ++t) {
      std::vector<VkAabbPositionsKHR> boxes;
      std::vector<std::uint32_t> indices;
      for (std::uint32_t b = bead_ranges[t].first; b < bead_ranges[t].first + bead_ranges[t].count; ++b) {
        const dvec3 centre(vec3(beads[b].centre_radius));
        const double radius = beads[b].centre_radius.w;
        indices.push_back(b);
        boxes.push_back(box_of(centre - radius, centre + radius));
      }
      levels[first_bead + t] = build_level(boxes, indices, first_bead + t, report.memory.nlas);
    }
  }

  // One triangle's distortion (placement/membrane_distortion.hpp), or nothing for one that owns no copy.
  std::optional<placement::MembraneDistortion> triangle_distortion(const gpu::Compartment& c, const gpu::RenderCompartment& rc,
                                                                   std::uint32_t t) const {
    const gpu::Triangle& tri = triangles[t];
    const std::uint32_t f = meshes[c.mesh].first_vertex;
    placement::MembraneTriangleCorners corners;
    const std::uint32_t v[3] = {tri.v0, tri.v1, tri.v2};
    for (int i = 0; i < 3; ++i) {
      corners.position[i] = vec3(vertex_positions[f + v[i]]);
      corners.normal[i] = vec3(vertex_normals[f + v[i]]);
      corners.uv[i] = vertex_uvs[f + v[i]];
    }
    return placement::triangle_distortion(corners, {rc.membrane.x, rc.membrane.y, rc.membrane.z, c.scales.w});
  }

  placement::DistortionClasses distortion_classes(const gpu::Compartment& c, const gpu::RenderCompartment& rc) const {
    const gpu::Mesh& mesh = meshes[c.mesh];
    std::vector<std::optional<placement::MembraneDistortion>> per(mesh.triangle_count);
    for (std::uint32_t k = 0; k < mesh.triangle_count; ++k) per[k] = triangle_distortion(c, rc, mesh.first_triangle + k);
    return placement::distortion_classes(per, rc.membrane.z);
  }

  // The M1-placed atoms of copy `m` (spheres included) as a box about its origin, from the atoms
  // themselves (the instance's stored AABB is not trusted for what the renderer may skip).
  std::pair<dvec3, dvec3> placed_extent(const gpu::MoleculeInstance& m) const {
    const gpu::MoleculeType& type = molecules[m.molecule_type];
    const glm::dquat q(double(m.rotation.w), double(m.rotation.x), double(m.rotation.y), double(m.rotation.z));
    const dmat3 r = glm::mat3_cast(glm::normalize(q));
    dvec3 lo(INFINITY), hi(-INFINITY);
    for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
      const dvec3 p = r * dvec3(vec3(atoms[a].centre_radius));
      const double radius = atoms[a].centre_radius.w;
      lo = glm::min(lo, p - radius), hi = glm::max(hi, p + radius);
    }
    return {lo, hi};
  }

  // Square t's molecule boxes in the sheared tile space of distortion d (copy_boxes). Grows
  // square_reach[t] to hold the copies in unsheared tile space.
  std::vector<VkAabbPositionsKHR> square_boxes(std::uint32_t t, const placement::MembraneDistortion& d, double half) {
    std::vector<VkAabbPositionsKHR> boxes;
    for (std::uint32_t m = tiles2d[t].first_instance; m < tiles2d[t].first_instance + tiles2d[t].instance_count; ++m) {
      const auto [atoms_lo, atoms_hi] = placed_extent(instances[m]);
      const placement::CopyBoxes b = placement::copy_boxes(dvec3(instances[m].position), (atoms_lo + atoms_hi) * 0.5, (atoms_hi - atoms_lo) * 0.5,
                                     type_radius[instances[m].molecule_type], d, half);
      boxes.push_back(box_of(b.lo, b.hi));
      square_reach[t].first = glm::min(square_reach[t].first, b.reach_lo);
      square_reach[t].second = glm::max(square_reach[t].second, b.reach_hi);
    }
    return boxes;
  }

  // The level record of square t's mLAS for distortion class k: class 0's at first_square, the other
  // classes' after the beads'.
  std::uint32_t square_level(std::uint32_t k, std::uint32_t t) const {
    return k == 0 ? first_square + t : first_class_square + (k - 1) * std::uint32_t(tiles2d.size()) + t;
  }

  // mLAS: per Wang square, molecule boxes in tile space widened by the distortion of every
  // compartment that uses the square; per Wang cube, bounding spheres' boxes in cube space.
  void build_tile_levels() {
    std::vector<std::array<std::optional<placement::MembraneDistortion>, placement::kDistortionClasses>> square_distortion(tiles2d.size());
    std::vector<double> square_half(tiles2d.size(), 0.0);  // the tile point of its lift planes
    for (std::uint32_t ci = 0; ci < compartments.size(); ++ci) {
      const gpu::Compartment& c = compartments[ci];
      if (c.membrane_recipe == gpu::NANO_NO_INDEX) continue;
      const placement::DistortionClasses classes = distortion_classes(c, render_compartments[ci]);
      // Per triangle, where its class's squares start, relative to class 0's (frame.levels.x).
      render_compartments[ci].core_skip.y = std::uint32_t(orders.size());
      for (std::size_t k = 0; k < classes.of_triangle.size(); ++k)
        orders.push_back((square_level(classes.of_triangle[k], 0) - first_square) |
                         (classes.unsheared[k] ? gpu::NANO_LIFT_UNSHEARED : 0u));
      for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t) {
        // A square belongs to one membrane's tile set, so every compartment using it has its tile size.
        square_half[t] = render_compartments[ci].membrane.z;
        for (std::uint32_t k = 0; k < placement::kDistortionClasses; ++k) {
          if (classes.bound[k]) placement::widen_to(square_distortion[t][k], *classes.bound[k]);
        }
      }
    }
    square_reach.assign(tiles2d.size(), {dvec3(INFINITY), dvec3(-INFINITY)});
    for (std::uint32_t t = 0; t < tiles2d.size(); ++t)
      for (std::uint32_t k = 0; k < placement::kDistortionClasses; ++k)
        if (square_distortion[t][k] && tiles2d[t].instance_count > 0)  // else no compartment renders it
          add_tile_level(square_level(k, t), square_boxes(t, *square_distortion[t][k], square_half[t]));
    build_replication_areas();
    if (options.two_level_membranes) build_atom_squares();
    for (std::uint32_t t = 0; t < tiles3d.size(); ++t) {
      if (tiles3d[t].instance_count == 0) continue;
      std::vector<VkAabbPositionsKHR> boxes;
      for (std::uint32_t m = tiles3d[t].first_instance; m < tiles3d[t].first_instance + tiles3d[t].instance_count; ++m) {
        const dvec3 pos(instances[m].position);
        const double e = type_radius[instances[m].molecule_type] + 0.01;
        boxes.push_back(box_of(pos - e, pos + e));
      }
      add_tile_level(first_cube + t, boxes);
    }
  }

  void build_kept_boxes() {
    const std::vector<std::uint32_t> kept = kept_boxes(*this, type_radius);
    section_buffers[gpu::NANO_B_KEPT_BOXES] = storage(std::as_bytes(std::span(kept)));
    report.memory.derived += section_buffers[gpu::NANO_B_KEPT_BOXES].size();
  }

  // repLAS per compartment: its W×H replication slots as boxes in the space of the area's origin tile
  // (slot (i, j) holds the union of the set's molecule boxes moved by (i·S, j·S)); orders hold the
  // slot index i + W·j. Every tile of a triangle shares M1's linear part, so one query finds the slots.
  void build_replication_areas() {
    for (std::uint32_t ci = 0; ci < compartments.size(); ++ci) {
      const gpu::Compartment& c = compartments[ci];
      render_compartments[ci].span.w = gpu::NANO_NO_INDEX;
      if (c.membrane_recipe == gpu::NANO_NO_INDEX) continue;
      dvec3 lo(INFINITY), hi(-INFINITY);
      for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t)
        lo = glm::min(lo, square_reach[t].first), hi = glm::max(hi, square_reach[t].second);
      if (!(lo.x <= hi.x)) continue;  // no molecules
      const double S = c.scales.y;
      std::vector<VkAabbPositionsKHR> boxes;
      std::vector<std::uint32_t> slots;
      for (std::uint32_t j = 0; j < c.replication_height; ++j)
        for (std::uint32_t i = 0; i < c.replication_width; ++i) {
          const dvec3 shift(i * S, j * S, 0.0);
          boxes.push_back(box_of(lo + shift, hi + shift));
          slots.push_back(i + c.replication_width * j);
        }
      levels[first_area + ci] = build_level(boxes, slots, first_area + ci, report.memory.mlas);
      render_compartments[ci].span.w = first_area + ci;
      large_replication_areas = large_replication_areas || slots.size() > gpu::NANO_DIRECT_SLOTS;
      const VkAabbPositionsKHR slot = box_of(lo, hi);
      render_compartments[ci].slot_lo = glm::vec4(slot.minX, slot.minY, slot.minZ, float(S));
      render_compartments[ci].slot_hi = glm::vec4(slot.maxX, slot.maxY, slot.maxZ, 0.f);
    }
  }

  // The paper's two-level design for membranes: per Wang square one BLAS of every atom of every
  // molecule, at its tile-space position p + R(q)·a (the affine tile placement, not the true M2:
  // measured against the oracle by verify). orders hold (molecule index in the tile, atom index).
  void build_atom_squares() {
    for (std::uint32_t t = 0; t < tiles2d.size(); ++t) {
      if (level_records[first_square + t].count == 0) continue;  // no compartment renders it
      std::vector<VkAabbPositionsKHR> boxes;
      std::vector<std::uint32_t> values;
      for (std::uint32_t m = 0; m < tiles2d[t].instance_count; ++m) {
        const gpu::MoleculeInstance& mi = instances[tiles2d[t].first_instance + m];
        const gpu::MoleculeType& type = molecules[mi.molecule_type];
        for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
          const dvec3 c = dvec3(mi.position) + dvec3(gpu::quat_rotate(mi.rotation, vec3(atoms[a].centre_radius)));
          const double r = atoms[a].centre_radius.w + 1e-3;
          boxes.push_back(box_of(c - r, c + r));
          values.push_back(m);
          values.push_back(a);
        }
      }
      levels[first_atom_square + t] = build_level(boxes, values, first_atom_square + t, report.memory.mlas, 2);
    }
  }

  // orders hold the molecule's index within its tile.
  void add_tile_level(std::uint32_t record, const std::vector<VkAabbPositionsKHR>& boxes) {
    std::vector<std::uint32_t> molecule(boxes.size());
    for (std::uint32_t i = 0; i < molecule.size(); ++i) molecule[i] = i;
    levels[record] = build_level(boxes, molecule, record, report.memory.mlas);
    ++report.mlas_count;
  }

  // The shell offsets of the chosen mode, parallel to section triangle_shells.
  std::vector<gpu::TriangleShell> mode_shells() const {
    std::vector<gpu::TriangleShell> out(triangle_shells.begin(), triangle_shells.end());
    const bool fixed = options.shell == ShellMode::fixed || options.shell == ShellMode::fixed_overlap;
    const bool overlap = options.shell == ShellMode::adaptive_overlap || options.shell == ShellMode::fixed_overlap;
    for (const gpu::Mesh& mesh : meshes) {
      gpu::ShellOffsets largest{0, 0, 0};
      for (std::uint32_t t = mesh.first_triangle; t < mesh.first_triangle + mesh.triangle_count; ++t)
        largest = gpu::shell_offsets_max(largest, {out[t].h_plus, out[t].h_minus, out[t].side_offset});
      for (std::uint32_t t = mesh.first_triangle; t < mesh.first_triangle + mesh.triangle_count; ++t) {
        gpu::TriangleShell& s = out[t];
        if (s.h_plus == 0 && s.h_minus == 0 && s.side_offset == 0) continue;  // owns nothing: no prism
        if (fixed) s.h_plus = largest.h_plus, s.h_minus = largest.h_minus, s.side_offset = largest.side;
        if (!overlap) s.side_offset = 0;
      }
    }
    return out;
  }

  // µLAS BLAS per compartment: Morton-sorted prism boxes (triangles that own molecules), then the
  // core grid widened by one box (the region the core renderer's DDA walks).
  void build_compartment_blases() {
    const std::vector<gpu::TriangleShell> shell_records = mode_shells();
    shell_buffer = storage(std::as_bytes(std::span(shell_records)));
    report.memory.derived += shell_buffer.size();
    compartment_blas.resize(compartments.size());
    for (std::uint32_t ci = 0; ci < compartments.size(); ++ci) {
      const gpu::Compartment& c = compartments[ci];
      gpu::RenderCompartment& rc = render_compartments[ci];
      std::vector<VkAabbPositionsKHR> prisms;
      std::vector<std::uint32_t> prism_triangles;
      if (c.membrane_recipe != gpu::NANO_NO_INDEX) {
        const gpu::Mesh& mesh = meshes[c.mesh];
        const std::uint32_t f = mesh.first_vertex;
        for (std::uint32_t tl = 0; tl < mesh.triangle_count; ++tl) {
          const gpu::TriangleShell& s = shell_records[mesh.first_triangle + tl];
          if (s.h_plus == 0 && s.h_minus == 0 && s.side_offset == 0) continue;
          const gpu::Triangle& tri = triangles[mesh.first_triangle + tl];
          const gpu::Prism pr = gpu::shell_prism_make(
              vec3(vertex_positions[f + tri.v0]), vec3(vertex_positions[f + tri.v1]), vec3(vertex_positions[f + tri.v2]),
              vec3(vertex_normals[f + tri.v0]), vec3(vertex_normals[f + tri.v1]), vec3(vertex_normals[f + tri.v2]),
              gpu::ShellOffsets{s.h_plus, s.h_minus, s.side_offset});
          vec3 lo = pr.v[0], hi = pr.v[0];
          for (int k = 1; k < 6; ++k) lo = glm::min(lo, pr.v[k]), hi = glm::max(hi, pr.v[k]);
          prisms.push_back(outward_box(lo, hi));
          prism_triangles.push_back(tl);
        }
      }
      const std::vector<std::uint32_t> order = morton_order(prisms);
      std::vector<VkAabbPositionsKHR> boxes;
      rc.counts.z = std::uint32_t(prisms.size());
      rc.counts.w = std::uint32_t(orders.size());
      for (std::uint32_t i : order) {
        boxes.push_back(prisms[i]);
        orders.push_back(prism_triangles[i]);
      }
      if (rc.span.z != 0) {
        const dvec3 B(c.grid_min.w);
        const dvec3 lo = dvec3(c.grid_min) - B;
        const dvec3 hi = dvec3(c.grid_min) + B * (dvec3(glm::uvec3(c.grid_dims)) + 1.0);
        boxes.push_back(outward_box(vec3(lo), vec3(hi)));
      }
      report.prisms += prisms.size();
      dvec3 lo(INFINITY), hi(-INFINITY);
      for (const VkAabbPositionsKHR& b : boxes)
        lo = glm::min(lo, dvec3(b.minX, b.minY, b.minZ)), hi = glm::max(hi, dvec3(b.maxX, b.maxY, b.maxZ));
      compartment_bounds.push_back({lo, hi});
      compartment_boxes.push_back(std::move(boxes));
      build_compartment_blas(ci, compartment_boxes.back());
    }
  }

  void build_compartment_blas(std::uint32_t ci, const std::vector<VkAabbPositionsKHR>& boxes) {
    if (compartment_blas[ci].handle() != VK_NULL_HANDLE) report.memory.ulas -= compartment_blas[ci].size();
    compartment_blas[ci] = {};
    if (boxes.empty()) return;
    const vk::Buffer input =
        vk::Buffer::with_data(device, std::as_bytes(std::span(boxes)), vk::kBuildInputUsage, vk::MemoryUse::DeviceLocal);
    compartment_blas[ci] = vk::build_bottom_level(device, vk::AabbGeometry{input.address(), std::uint32_t(boxes.size())});
    report.memory.ulas += compartment_blas[ci].size();
    note_scratch(compartment_blas[ci]);
  }

  // After the flat level's choice changed: a compartment with one instance gets its µLAS BLAS again
  // with each flattened triangle's prism box shrunk to the point at its centre, so traversal all
  // but never meets it (a ray through that very point is a candidate the shader skips by the
  // triangle's bit; a NaN box, "inactive" by the Vulkan spec, lost neighbouring prisms on
  // lavapipe). Compartments shared by several instances keep every prism; the shader skips
  // flattened ones by their bit, each µLAS candidate still costing a callback.
  void deactivate_flattened_prisms() {
    std::vector<std::uint32_t> instance_count(compartments.size(), 0), sole_instance(compartments.size(), 0);
    for (std::uint32_t i = 0; i < compartment_instances.size(); ++i)
      ++instance_count[compartment_instances[i].compartment], sole_instance[compartment_instances[i].compartment] = i;
    for (std::uint32_t ci = 0; ci < compartments.size(); ++ci) {
      if (instance_count[ci] != 1 || render_compartments[ci].counts.z == 0) continue;
      const gpu::RenderCompartment& rc = render_compartments[ci];
      std::vector<VkAabbPositionsKHR> boxes = compartment_boxes[ci];
      for (std::uint32_t prim = 0; prim < rc.counts.z; ++prim)
        if (flat->flattened(sole_instance[ci], orders[rc.counts.w + prim])) {
          VkAabbPositionsKHR& b = boxes[prim];
          const float x = 0.5f * (b.minX + b.maxX), y = 0.5f * (b.minY + b.maxY), z = 0.5f * (b.minZ + b.maxZ);
          b = {x, y, z, x, y, z};
        }
      build_compartment_blas(ci, boxes);
    }
  }

  void upload_derived() {
    render_compartment_buffer = storage(std::as_bytes(std::span(render_compartments)));
    flat = std::make_unique<FlatLevel>(device, p, [this](std::uint32_t type) -> const vk::AccelerationStructure* {
      return type < molecules.size() && level_records[type].count > 0 ? &levels[type].blas : nullptr;
    });
    flat_triangle_buffer = vk::Buffer(device, flat->triangle_bits().size() * sizeof(std::uint32_t),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
    flat_triangle_buffer.write(std::as_bytes(std::span(flat->triangle_bits())));
    std::uint64_t base = 0;
    for (std::uint32_t i = 0; i < compartment_instances.size(); ++i) {
      const gpu::CompartmentInstance& ci = compartment_instances[i];
      render_instances.push_back(
          {glm::uvec4(std::uint32_t(base), std::uint32_t(base >> 32), ci.compartment, flat->first_bit(i)), {}, {}, {}});
      const gpu::RenderCompartment& rc = render_compartments[ci.compartment];
      const gpu::Compartment& c = compartments[ci.compartment];
      const std::uint64_t core_span =
          rc.span.z ? std::uint64_t{c.grid_dims.x} * c.grid_dims.y * c.grid_dims.z * rc.counts.y : 0;
      base += (std::uint64_t{rc.span.y} << 32 | rc.span.x) + core_span;
    }
    medium_number_base = base;
    render_instance_buffer = vk::Buffer(device, render_instances.size() * sizeof(gpu::RenderInstance),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
    level_buffer = storage(std::as_bytes(std::span(level_records)));
    order_buffer = storage(std::as_bytes(std::span(orders)));
    const gpu::FlatCopy none{};
    flat_placeholder = storage(std::as_bytes(std::span(&none, 1)));
    report.memory.derived += render_compartment_buffer.size() + render_instance_buffer.size() + level_buffer.size() +
                             order_buffer.size() + flat_placeholder.size() + flat_triangle_buffer.size();
  }

  void set_eye(const dvec3& eye, std::span<const format::InstanceTransform> moved) {
    if (!moved.empty() && moved.size() != compartment_instances.size())
      throw std::invalid_argument("set_eye: " + std::to_string(moved.size()) + " transforms for " +
                                  std::to_string(compartment_instances.size()) + " compartment instances");
    if (flat->select(flatten_camera, moved.empty() ? flatten_budget : 0, flatten_both_sides, flatten_new_copies)) {
      flat_triangle_buffer.write(std::as_bytes(std::span(flat->triangle_bits())));
      deactivate_flattened_prisms();
      report.memory.flat = flat->memory_bytes();
      report.flattened_copies = flat->copies();
      report.flattened_triangles = flat->triangles();
      report.flat_seconds = flat->last_build_seconds();
    }
    std::vector<VkAccelerationStructureInstanceKHR> unsorted;
    std::vector<VkAabbPositionsKHR> world_boxes;  // each instance's box, for the build order
    for (std::uint32_t i = 0; i < compartment_instances.size(); ++i) {
      const gpu::CompartmentInstance& ci = compartment_instances[i];
      if (compartment_blas[ci.compartment].handle() == VK_NULL_HANDLE) continue;
      const format::InstanceTransform t = moved.empty() ? format::instance_transform(ci) : moved[i];
      if (!(std::abs(glm::determinant(t.linear)) > 1e-12)) throw std::invalid_argument("set_eye: singular instance transform");
      glm::dmat4 m(t.linear);
      m[3] = glm::dvec4(t.translation - eye, 1.0);
      // The eye in compartment space, L⁻¹(eye − T), in double, split into two floats; L⁻¹ by rows.
      const glm::dmat3 from_world = glm::inverse(glm::dmat3(m));
      const dvec3 eye_c = from_world * -dvec3(m[3]);
      const vec3 hi(eye_c);
      render_instances[i].eye_hi = glm::vec4(hi, 0.f);
      render_instances[i].eye_lo = glm::vec4(vec3(eye_c - dvec3(hi)), 0.f);
      for (int r = 0; r < 3; ++r) render_instances[i].from_world[r] = glm::vec4(vec3(glm::row(from_world, r)), 0.f);
      const std::uint8_t mask = visibility.compartment_hidden(ci.compartment) ? 0x00 : 0xFF;  // rays query with 0xFF
      unsorted.push_back(vk::make_instance(compartment_blas[ci.compartment], m, i, mask));
      const auto& [lo, hi_c] = compartment_bounds[ci.compartment];
      dvec3 w_lo(INFINITY), w_hi(-INFINITY);
      for (int corner = 0; corner < 8; ++corner) {
        const dvec3 p((corner & 1) ? hi_c.x : lo.x, (corner & 2) ? hi_c.y : lo.y, (corner & 4) ? hi_c.z : lo.z);
        const dvec3 w = dvec3(m * glm::dvec4(p, 1.0));
        w_lo = glm::min(w_lo, w), w_hi = glm::max(w_hi, w);
      }
      world_boxes.push_back(box_of(w_lo, w_hi));
    }
    if (has_ulas) report.memory.ulas -= ulas.size();
    has_ulas = !unsorted.empty();
    if (!has_ulas) fail("compartment_instances", "the package places nothing to render");
    // Morton order, as every other build here: lavapipe splits in input order, and a thousand cells
    // in the order the baker placed them made a µLAS whose nodes overlap (1000 cells: frames 2.2×
    // one cell's with the same candidates per pixel). The custom index keeps naming the instance.
    std::vector<VkAccelerationStructureInstanceKHR> records;
    records.reserve(unsorted.size());
    for (const std::uint32_t k : morton_order(world_boxes)) records.push_back(unsorted[k]);
    ulas = vk::build_top_level(device, std::span(records));
    note_scratch(ulas);
    render_instance_buffer.write(std::as_bytes(std::span(render_instances)));
    report.memory.ulas += ulas.size();
    if (has_medium()) {
      if (!moved.empty()) build_medium_instances(moved);
      else if (moved_medium) build_medium_instances(package_transforms());
      moved_medium = !moved.empty();
      const double B = medium[0].region_min.w;
      const dvec3 eye_region = eye - dvec3(medium[0].region_min);
      const dvec3 box = glm::clamp(glm::floor(eye_region / B), dvec3(-1e9), dvec3(1e9));
      const dvec3 within = eye_region - box * B;
      const vec3 hi(within);
      render_medium.eye_box = glm::ivec4(glm::ivec3(box), 0);
      render_medium.eye_hi = glm::vec4(hi, 0.f);
      render_medium.eye_lo = glm::vec4(vec3(within - dvec3(hi)), 0.f);
    }
    render_medium_buffer.write(std::as_bytes(std::span(&render_medium, 1)));
  }
  bool moved_medium = false;  // the medium's records follow moved instances (animation)

  placement::Visibility visibility;
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
const format::Package& GpuScene::package() const { return impl_->p; }

void GpuScene::write_descriptors(VkDescriptorSet set) const {
  const Impl& s = *impl_;
  if (!s.has_ulas) throw std::logic_error("GpuScene::write_descriptors before set_eye");
  const VkDevice d = s.device.handle();
  vk::write_acceleration_structure(d, set, gpu::NANO_B_ULAS, s.ulas);
  for (std::uint32_t b = gpu::NANO_B_MOLECULES; b <= gpu::NANO_B_MASK_WORDS; ++b) {
    if (b == gpu::NANO_B_TRIANGLE_SHELLS) continue;
    vk::write_storage_buffer(d, set, b, s.section_buffers[b]);
  }
  for (std::uint32_t b : {gpu::NANO_B_TRIANGLE_DROPS, gpu::NANO_B_DROPPED_COPIES, gpu::NANO_B_BEADS, gpu::NANO_B_CORE_SKIP,
                         gpu::NANO_B_KEPT_BOXES})
    vk::write_storage_buffer(d, set, b, s.section_buffers[b]);
  for (std::uint32_t b : {gpu::NANO_B_MEDIUM, gpu::NANO_B_EXCLUSION_FIELDS, gpu::NANO_B_EXCLUSION_VALUES})
    vk::write_storage_buffer(d, set, b, s.section_buffers[b]);
  vk::write_storage_buffer(d, set, gpu::NANO_B_MEDIUM_INSTANCES, s.medium_instance_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_RENDER_MEDIUM, s.render_medium_buffer);
  vk::write_acceleration_structure(d, set, gpu::NANO_B_EXCLUSION_TLAS, s.exclusion_tlas);
  vk::write_storage_buffer(d, set, gpu::NANO_B_TRIANGLE_SHELLS, s.shell_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_RENDER_COMPARTMENTS, s.render_compartment_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_RENDER_INSTANCES, s.render_instance_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_LEVELS, s.level_buffer);
  vk::write_storage_buffer(d, set, gpu::NANO_B_ORDERS, s.order_buffer);
    const bool flat = !s.flat->empty();
  vk::write_acceleration_structure(d, set, gpu::NANO_B_FLAT_TLAS, flat ? s.flat->tlas() : s.ulas);
  vk::write_storage_buffer(d, set, gpu::NANO_B_FLAT_COPIES, flat ? s.flat->copy_records() : s.flat_placeholder);
  vk::write_storage_buffer(d, set, gpu::NANO_B_FLAT_TRIANGLES, s.flat_triangle_buffer);
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
