#pragma once
// Explicit instancing on the device, the conventional design virtual instancing is compared with
// (issue #7 item 5): every molecule copy the CPU oracle enumerates (oracle::ExplicitScene) becomes
// one instance of one TLAS, referencing its molecule type's BLAS of atom boxes. Memory therefore
// grows with the copy count — 64 bytes of VkAccelerationStructureInstanceKHR, 16 bytes of copy
// record and the TLAS's own nodes per copy — where the virtual scene (render::GpuScene) grows with
// the number of distinct tiles. Traced by shaders/explicit_instancing/instanced.comp (InstancedRenderer).
//
// Precision: TLAS transforms are float. They are taken relative to an anchor — the centre of the
// copies' bounds, fixed at load (the conventional build-once TLAS), or the camera's eye when
// InstancedOptions::eye_relative asks for a rebuild per camera as GpuScene::set_eye does — so
// a scene far from the world origin keeps its precision near itself.
#include <cstdint>
#include <memory>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <vulkan/vulkan.h>

#include "format/package.hpp"
#include "runtime/vk/device.hpp"

namespace nano::explicit_instancing {

struct InstancedOptions {
  // Refuse scenes with more molecule copies (InputError naming the package): explicit instancing's
  // memory is proportional to them. At most 2^24 (the instance custom index holds the copy index).
  std::uint64_t max_copies = 2'000'000;
  // Rebuild the TLAS relative to every camera's eye (render time then includes a TLAS build over
  // all copies); false: built once, relative to the scene's centre.
  bool eye_relative = false;
};

// Device memory by category, bytes.
struct InstancedMemory {
  std::uint64_t blas = 0;             // one BLAS of atom boxes per molecule type
  std::uint64_t tlas = 0;             // the one TLAS over every copy
  std::uint64_t instance_buffer = 0;  // VkAccelerationStructureInstanceKHR per copy (build input, kept for rebuilds)
  std::uint64_t copy_records = 0;     // per copy: copy number and molecule type (16 bytes)
  std::uint64_t atoms = 0;            // atom spheres, BLAS primitive → atom orders, molecule type records
  std::uint64_t scratch_peak = 0;     // largest build scratch (freed after each build; not in total)
  std::uint64_t total() const { return blas + tlas + instance_buffer + copy_records + atoms; }
};

struct InstancedReport {
  double enumerate_seconds = 0;  // the oracle's copy enumeration (host)
  double blas_seconds = 0;       // molecule-type BLASes (Morton sort, upload, build)
  double tlas_seconds = 0;       // instance records (Morton sort, upload) and the TLAS build
  InstancedMemory memory;
  std::uint64_t copies = 0;          // every copy the oracle enumerates
  std::uint64_t instances = 0;       // TLAS instances: copies of molecule types that have atoms
  std::uint64_t molecule_types = 0;  // BLASes built (types with atoms)
  std::uint64_t blas_atoms = 0;      // primitives over all BLASes
  double seconds() const { return enumerate_seconds + blas_seconds + tlas_seconds; }
};
nlohmann::json to_json(const InstancedReport& report);


class InstancedScene {
public:
  // `package` must have passed format::validate_semantics and must outlive this object. Throws
  // nano::InputError naming the package for more than options.max_copies copies or a scene with
  // nothing to render, std::invalid_argument for max_copies above 2^24.
  InstancedScene(const vk::Device& device, const format::Package& package, const InstancedOptions& options = {});
  ~InstancedScene();
  InstancedScene(InstancedScene&&) noexcept;

  // Readies the TLAS for a camera at world position `eye` (rebuilds it when eye_relative) and
  // returns the ray origin in the TLAS's space: eye − anchor, subtracted in double.
  glm::vec3 prepare(const glm::dvec3& eye);

  // Writes the scene's bindings (0 .. NANO_INSTANCED_SCENE_BINDING_COUNT − 1, shaders/shared/bindings.h) of the instanced pipeline's set.
  void write_descriptors(VkDescriptorSet set) const;

  const format::Package& package() const;
  const InstancedReport& report() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::explicit_instancing
