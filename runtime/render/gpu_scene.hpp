#pragma once
// A validated package on the device: its sections as storage buffers, the records the renderer
// derives from them (shaders/shared/render_scene.h) and the acceleration structures of the three
// levels — one nLAS per molecule type, one mLAS per Wang square and cube, and the µLAS over the
// compartment instances, rebuilt relative to the eye for every camera (precision far from the origin).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <vulkan/vulkan.h>

#include "common/error.hpp"
#include "format/package.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/visibility.hpp"
#include "runtime/vk/acceleration_structure.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::render {

// The four shells of the paper's comparison. Without overlap (side offset 0) molecules that cross
// a triangle's edge lose the part outside its prism; the fixed shells use each mesh's largest offsets.
enum class ShellMode { adaptive_overlap, adaptive, fixed_overlap, fixed };
ShellMode parse_shell_mode(std::string_view text, const InputSource& source);  // an InputError names the choices
const char* to_string(ShellMode mode);

struct SceneOptions {
  ShellMode shell = ShellMode::adaptive_overlap;
  // Also build the paper's two-level membrane tiles (every atom of a Wang square in one BLAS) for
  // `--levels 2`; costs memory, so only on request.
  bool two_level_membranes = false;
};

// Device memory by category, bytes.
struct MemoryReport {
  std::uint64_t package_data = 0;      // the package's sections copied to device memory
  std::uint64_t package_imported = 0;  // sections the device reads in place from the mapped file
                                       // (VK_EXT_external_memory_host on a device sharing host memory)
  std::uint64_t derived = 0;       // render records, primitive orders, shells of the chosen mode
  std::uint64_t nlas = 0;          // molecule types (BLAS of atom boxes + TLAS)
  std::uint64_t mlas = 0;          // Wang squares and cubes
  std::uint64_t ulas = 0;          // per-compartment prism BLASes + the instance TLAS
  std::uint64_t flat = 0;          // the flat level (flat_level.hpp), when it holds copies
  std::uint64_t scratch_peak = 0;  // largest build scratch (freed after each build; not in total)
  // Device-side allocations; imported pages are the package's own mapping, not counted here.
  std::uint64_t total() const { return package_data + derived + nlas + mlas + ulas + flat; }
};

struct LoadReport {
  double upload_seconds = 0, nlas_seconds = 0, mlas_seconds = 0, ulas_seconds = 0;
  MemoryReport memory;
  std::uint64_t nlas_count = 0, mlas_count = 0, prisms = 0;
  std::uint64_t flattened_copies = 0;  // copies in the flat level after the last set_eye
  std::uint64_t flattened_triangles = 0;
  double flat_seconds = 0;             // its last (re)build: enumeration, upload, TLAS
  std::uint64_t sections_imported = 0, sections_copied_from_pages = 0;
};
nlohmann::json to_json(const LoadReport& report);


class GpuScene {
public:
  // `package` must have passed format::validate_semantics and must outlive this object. Throws
  // nano::InputError for what the renderer needs beyond the validator (membranes without
  // triangle_shells, cube molecules reaching farther than one box, more than 2^24 instances).
  GpuScene(const vk::Device& device, const format::Package& package, const SceneOptions& options = {});
  ~GpuScene();
  GpuScene(GpuScene&&) noexcept;

  // (Re)builds the µLAS with instance translations relative to `eye` (world Å): the shader's rays
  // start at the origin, so far-from-origin scenes keep their precision near the camera.
  void set_eye(const glm::dvec3& eye);
  // The same with every compartment instance moved to `transforms` (one per instance, animation):
  // only the µLAS changes, never the mLAS or nLAS. Throws std::invalid_argument for a wrong count
  // or a singular transform.
  void set_eye(const glm::dvec3& eye, std::span<const format::InstanceTransform> transforms);

  // The device memory the flat level (flat_level.hpp) may take from the next set_eye on, and the
  // view it chooses for: the membrane copies of the triangles that cover most pixels of `camera`
  // and fit are flattened, the µLAS skips them (`both_sides`: back faces count too, as when
  // clipping opens the membrane). 0 (the default) traces every copy virtually; so does set_eye with
  // moved transforms.
  // `new_copies`: FlatLevel::select's bound on copies enumerated per set_eye.
  void set_flatten(std::uint64_t bytes, const gpu::Camera& camera, bool both_sides,
                   std::uint64_t new_copies = ~std::uint64_t{0});
  // What the next frames leave out (--hide): a hidden compartment's instances get µLAS mask 0 from
  // the next set_eye on, so no ray meets them; a hidden molecule type's nLAS and bead level read as
  // empty (RenderLevel.count 0). The medium's exclusion stays: a hidden cell keeps its place empty.
  // The flat level must be off while anything is hidden (it holds copies of every type).
  void set_visibility(const placement::Visibility& visibility);

  // The flat level's RenderFrame.flat_eye for a camera at world position `eye` (w = 0: empty level).
  glm::vec4 flat_eye(const glm::dvec3& eye) const;

  const format::Package& package() const;

  // Writes the scene's bindings (0 .. NANO_SCENE_BINDING_COUNT − 1, shaders/shared/bindings.h) of the render pipeline's set. Call after set_eye.
  void write_descriptors(VkDescriptorSet set) const;

  // Render-frame level table offsets (RenderFrame.levels).
  std::uint32_t first_square_level() const;
  std::uint32_t first_cube_level() const;
  std::uint32_t first_atom_square_level() const;  // valid with SceneOptions::two_level_membranes
  std::uint32_t first_bead_level() const;         // then one bead level per molecule type (package_records.h Bead)
  bool has_beads() const;                         // the package holds the level of detail (format ≥ 2.5)
  bool has_medium() const;                        // the package holds a medium (format ≥ 2.8)
  // Some compartment's replication area has more than NANO_DIRECT_SLOTS slots, so a prism may walk
  // its slots through the repLAS; without one the pipeline leaves that traversal out.
  bool has_large_replication_areas() const;
  std::uint32_t molecule_type_count() const;

  const LoadReport& report() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::render
