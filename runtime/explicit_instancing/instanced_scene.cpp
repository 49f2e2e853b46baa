#include "runtime/explicit_instancing/instanced_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "format/package_view.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "runtime/render/morton.hpp"
#include "runtime/vk/acceleration_structure.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"
#include "shared/instanced_records.h"

namespace nano::explicit_instancing {
namespace {

using glm::dvec3;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

using CopyRecord = gpu::InstancedCopy;
using TypeRecord = gpu::InstancedType;
static_assert(sizeof(VkAccelerationStructureInstanceKHR) == 64);

// The instance custom index (24 bits) names the copy.
constexpr std::uint64_t kCopyLimit = std::uint64_t{1} << 24;

// One copy as the oracle placed it, kept until the instance records are written.
struct Placed {
  dvec3 origin;       // world position of the molecule origin
  glm::mat3 linear;   // molecule → world linear part (float: what the TLAS transform holds)
  std::uint64_t number;
  std::uint32_t type;
  float radius;       // world bounding radius (Morton sort only)
};

VkAabbPositionsKHR box_of(const dvec3& lo, const dvec3& hi) {
  return {float(lo.x), float(lo.y), float(lo.z), float(hi.x), float(hi.y), float(hi.z)};
}

}  // namespace

nlohmann::json to_json(const InstancedReport& r) {
  const InstancedMemory& m = r.memory;
  return {{"seconds",
           {{"enumerate", r.enumerate_seconds}, {"blas", r.blas_seconds}, {"tlas", r.tlas_seconds}, {"total", r.seconds()}}},
          {"device_memory_bytes", m.total()},
          {"device_memory",
           {{"blas", m.blas},
            {"tlas", m.tlas},
            {"instance_buffer", m.instance_buffer},
            {"copy_records", m.copy_records},
            {"atoms", m.atoms},
            {"scratch_peak", m.scratch_peak}}},
          {"copies", r.copies},
          {"instances", r.instances},
          {"molecule_types", r.molecule_types},
          {"blas_atoms", r.blas_atoms}};
}

struct InstancedScene::Impl : format::PackageView {
  const vk::Device& device;
  const format::Package& p;
  InstancedOptions options;
  InstancedReport report;

  std::vector<vk::AccelerationStructure> blas;  // per molecule type; empty handle: no atoms
  vk::AccelerationStructure tlas;
  vk::Buffer instance_buffer, copy_buffer, type_buffer, atom_buffer, order_buffer;
  dvec3 anchor{0.0};  // world point the TLAS transforms are relative to
  // Kept only for eye_relative rebuilds: the records and the double origins their translations come from.
  std::vector<VkAccelerationStructureInstanceKHR> host_instances;
  std::vector<dvec3> host_origins;

  Impl(const vk::Device& d, const format::Package& package, const InstancedOptions& o)
      : PackageView(package), device(d), p(package), options(o) {
    if (options.max_copies > kCopyLimit)
      throw std::invalid_argument("InstancedOptions::max_copies above 2^24: the TLAS instance custom index that names "
                                  "a copy has 24 bits");
    // Everything on the host first: a refused scene never allocates device memory.
    auto start = std::chrono::steady_clock::now();
    std::vector<Placed> placed = enumerate();
    report.enumerate_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    build_molecule_types();
    report.blas_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    build_instances(placed);
    report.tlas_seconds = seconds_since(start);
  }

  [[noreturn]] void fail(const std::string& where, const std::string& rule) const { throw InputError(p.name(), where, rule); }

  // Every copy in the whole world; stops (throws) as soon as the limit is passed, so the refusal
  // costs at most max_copies copies of host memory.
  std::vector<Placed> enumerate() {
    if (p.record_count(format::SectionKind::medium) > 0)
      fail("medium", "the package's medium fills its region with ~10^9 copies or more, one TLAS instance each under "
                     "explicit instancing: render it with virtual instancing");
    const oracle::ExplicitScene scene(p);
    std::vector<Placed> placed;
    scene.for_each_copy(oracle::WorldBox::everything(), [&](const oracle::Copy& c) {
      if (++report.copies > options.max_copies)
        fail("copies", "more than " + std::to_string(options.max_copies) +
                           " molecule copies: explicit instancing keeps one 64-byte TLAS instance (plus TLAS nodes "
                           "and a 16-byte record) per copy; " +
                           (options.max_copies < kCopyLimit ? "raise InstancedOptions::max_copies (at most 2^24) or render "
                                                              "with virtual instancing"
                                                            : "the 24-bit instance custom index allows no more: render "
                                                              "with virtual instancing"));
      if (c.molecule_type >= molecules.size())
        fail("copies", "a copy names molecule type " + std::to_string(c.molecule_type) + " of " +
                           std::to_string(molecules.size()));
      if (molecules[c.molecule_type].atom_count == 0) return;  // nothing to hit
      placed.push_back({c.origin, glm::mat3(c.linear), c.number, c.molecule_type, float(c.radius)});
    });
    if (placed.empty()) fail("copies", "the package places no molecule with atoms: nothing to render");
    return placed;
  }

  void note_scratch(const vk::AccelerationStructure& s) {
    report.memory.scratch_peak = std::max<std::uint64_t>(report.memory.scratch_peak, s.scratch_size());
  }

  // Per molecule type a BLAS of its atom boxes in molecule space, Morton-sorted (lavapipe splits at
  // the median in input order); orders map BLAS primitive → atom index, as GpuScene's nLAS does.
  void build_molecule_types() {
    std::vector<TypeRecord> types(molecules.size(), TypeRecord{glm::uvec4(0), glm::vec4(0.0f)});
    std::vector<std::uint32_t> orders;
    blas.resize(molecules.size());
    for (std::uint32_t t = 0; t < molecules.size(); ++t) {
      const gpu::MoleculeType& m = molecules[t];
      types[t].colour = m.colour;
      if (m.atom_count == 0) continue;
      if (std::uint64_t{m.first_atom} + m.atom_count > atoms.size())
        fail("molecules[" + std::to_string(t) + "]", "atom range beyond section atoms");
      std::vector<VkAabbPositionsKHR> boxes;
      for (std::uint32_t a = m.first_atom; a < m.first_atom + m.atom_count; ++a) {
        const dvec3 c(atoms[a].centre_radius);
        const double r = atoms[a].centre_radius.w + 1e-3;  // a float-safe margin: the sphere test decides
        boxes.push_back(box_of(c - r, c + r));
      }
      const std::vector<std::uint32_t> order = render::morton_order(boxes);
      std::vector<VkAabbPositionsKHR> sorted;
      sorted.reserve(boxes.size());
      types[t].range = glm::uvec4(std::uint32_t(orders.size()), m.atom_count, 0u, 0u);
      for (std::uint32_t i : order) {
        sorted.push_back(boxes[i]);
        orders.push_back(m.first_atom + i);
      }
      const vk::Buffer input =
          vk::Buffer::with_data(device, std::as_bytes(std::span(sorted)), vk::kBuildInputUsage, vk::MemoryUse::DeviceLocal);
      blas[t] = vk::build_bottom_level(device, vk::AabbGeometry{input.address(), std::uint32_t(sorted.size())});
      report.memory.blas += blas[t].size();
      note_scratch(blas[t]);
      ++report.molecule_types;
      report.blas_atoms += sorted.size();
    }
    const auto storage = [&](std::span<const std::byte> bytes) {
      return vk::Buffer::with_data(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::DeviceLocal);
    };
    atom_buffer = storage(std::as_bytes(atoms));  // gpu::Atom is the shader's vec4; non-empty: some type has atoms
    order_buffer = storage(std::as_bytes(std::span(orders)));
    type_buffer = storage(std::as_bytes(std::span(types)));
    report.memory.atoms = atom_buffer.size() + order_buffer.size() + type_buffer.size();
  }

  // The instance records in Morton order of the copies' bounds (the TLAS build splits in input order
  // too), their copy records in the same order (custom index = position), and the TLAS.
  void build_instances(const std::vector<Placed>& placed) {
    dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Placed& c : placed) lo = glm::min(lo, c.origin), hi = glm::max(hi, c.origin);
    anchor = 0.5 * (lo + hi);
    std::vector<VkAabbPositionsKHR> bounds;
    bounds.reserve(placed.size());
    for (const Placed& c : placed) bounds.push_back(box_of(c.origin - anchor - double(c.radius), c.origin - anchor + double(c.radius)));
    const std::vector<std::uint32_t> order = render::morton_order(bounds);
    bounds = {};

    std::vector<VkAccelerationStructureInstanceKHR> records;
    std::vector<CopyRecord> copy_records;
    records.reserve(placed.size());
    copy_records.reserve(placed.size());
    if (options.eye_relative) host_origins.reserve(placed.size());
    for (std::uint32_t i : order) {
      const Placed& c = placed[i];
      glm::dmat4 m(glm::dmat3(c.linear));
      m[3] = glm::dvec4(c.origin - anchor, 1.0);
      const auto index = std::uint32_t(copy_records.size());  // < 2^24: max_copies is
      records.push_back(vk::make_instance(blas[c.type], m, index));
      copy_records.push_back({std::uint32_t(c.number), std::uint32_t(c.number >> 32), c.type, 0u});
      if (options.eye_relative) host_origins.push_back(c.origin);
    }
    report.instances = records.size();
    copy_buffer = vk::Buffer::with_data(device, std::as_bytes(std::span(copy_records)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        vk::MemoryUse::DeviceLocal);
    report.memory.copy_records = copy_buffer.size();
    // Host-visible so an eye-relative rebuild rewrites the translations in place.
    instance_buffer = vk::Buffer(device, records.size() * sizeof(VkAccelerationStructureInstanceKHR), vk::kBuildInputUsage,
                                 vk::MemoryUse::HostVisible);
    report.memory.instance_buffer = instance_buffer.size();
    instance_buffer.write(std::as_bytes(std::span(records)));
    build_tlas();
    if (options.eye_relative) host_instances = std::move(records);
  }

  void build_tlas() {
    if (tlas.handle() != VK_NULL_HANDLE) report.memory.tlas -= tlas.size();
    tlas = vk::build_top_level(device, instance_buffer.address(), std::uint32_t(report.instances));
    report.memory.tlas += tlas.size();
    note_scratch(tlas);
  }

  glm::vec3 prepare(const dvec3& eye) {
    if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
      throw std::invalid_argument("InstancedScene::prepare: the eye must be finite");
    if (options.eye_relative && eye != anchor) {
      anchor = eye;
      for (std::size_t i = 0; i < host_instances.size(); ++i)
        for (int r = 0; r < 3; ++r) host_instances[i].transform.matrix[r][3] = float(host_origins[i][r] - eye[r]);
      instance_buffer.write(std::as_bytes(std::span(host_instances)));
      build_tlas();
    }
    return glm::vec3(eye - anchor);
  }

  void write_descriptors(VkDescriptorSet set) const {
    const VkDevice d = device.handle();
    vk::write_acceleration_structure(d, set, gpu::NANO_IB_TLAS, tlas);
    vk::write_storage_buffer(d, set, gpu::NANO_IB_COPIES, copy_buffer);
    vk::write_storage_buffer(d, set, gpu::NANO_IB_TYPES, type_buffer);
    vk::write_storage_buffer(d, set, gpu::NANO_IB_ATOMS, atom_buffer);
    vk::write_storage_buffer(d, set, gpu::NANO_IB_ORDERS, order_buffer);
  }
};

InstancedScene::InstancedScene(const vk::Device& device, const format::Package& package, const InstancedOptions& options)
    : impl_(std::make_unique<Impl>(device, package, options)) {}
InstancedScene::~InstancedScene() = default;
InstancedScene::InstancedScene(InstancedScene&&) noexcept = default;

glm::vec3 InstancedScene::prepare(const glm::dvec3& eye) { return impl_->prepare(eye); }
void InstancedScene::write_descriptors(VkDescriptorSet set) const { impl_->write_descriptors(set); }
const format::Package& InstancedScene::package() const { return impl_->p; }
const InstancedReport& InstancedScene::report() const { return impl_->report; }

}  // namespace nano::explicit_instancing
