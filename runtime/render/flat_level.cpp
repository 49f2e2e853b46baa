#include "runtime/render/flat_level.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <stdexcept>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "common/singular_value.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/copy_enumerator.hpp"
#include "runtime/render/morton.hpp"
#include "shared/render_scene.h"

namespace nano::render {
namespace {

using glm::dvec3;
using glm::vec3;

// The instance custom index (24 bits) names the copy record.
constexpr std::uint64_t kCopyLimit = std::uint64_t{1} << 24;

// The float box of the ball of `radius` about `centre`, relative to `origin` (Morton keys only).
VkAabbPositionsKHR ball_box(const dvec3& centre, double radius, const dvec3& origin) {
  const dvec3 lo = centre - origin - radius, hi = centre - origin + radius;
  return {float(lo.x), float(lo.y), float(lo.z), float(hi.x), float(hi.y), float(hi.z)};
}

// One copy as placement::CopyEnumerator placed it.
struct Placed {
  dvec3 origin;      // world position of the molecule origin
  glm::mat3 linear;  // molecule → world linear part
  float radius;      // world bounding radius (Morton sort only)
  gpu::FlatCopy record;
};

// A triangle of one compartment instance: what select() ranks and takes whole.
struct FlatTriangle {
  dvec3 centroid{0.0};  // world
  dvec3 normal{0.0};    // world unit normal (the mesh's winding: outward for a closed oriented mesh)
  double area = 0;      // world Å²
  double radius = 0;    // world distance from the centroid to its farthest corner
  bool owns = false;    // its shell is not empty (a triangle without offsets owns no copy)
};

// Flattening a copy costs its share of a TLAS rebuild whenever the choice changes (~1 µs a copy on
// lavapipe, every frame of an orbit) and saves the virtual traversal of each pixel it covers
// (~40 µs a pixel on the virion's membrane): a triangle whose copies cover fewer pixels than this
// each is not worth its place (a whole red blood cell in view is 10⁻⁴ pixels a copy).
constexpr double kMinPixelsPerCopy = 0.05;

}  // namespace

struct FlatLevel::Impl : format::PackageView {
  const vk::Device& device;
  const format::Package& p;
  std::function<const vk::AccelerationStructure*(std::uint32_t)> molecule_blas;
  std::unique_ptr<placement::CopyEnumerator> enumerator;  // made on the first non-empty choice
  // Per compartment instance: its first bit, a sphere around its mesh (world), and its triangles in
  // the world, made the first time the instance could matter (a scene of a thousand cells keeps
  // only those ever near the eye).
  std::vector<std::uint32_t> instance_first_bit;
  std::uint32_t total_bits = 0;
  std::vector<dvec3> instance_centres;
  std::vector<double> instance_radii;
  std::vector<std::optional<std::vector<FlatTriangle>>> instance_triangles;
  std::unordered_map<std::uint32_t, std::vector<Placed>> cache;  // per bit, once enumerated
  std::uint64_t cached_copies = 0;
  std::vector<double> densities;  // per compartment instance: mean membrane copies per world Å²
  std::uint64_t capacity_budget = 0, capacity_copies = 0;  // the last budget and the copies it holds
  std::vector<std::uint32_t> chosen;  // bits, ascending
  std::vector<std::uint32_t> bits;  // chosen, 32 a word
  std::uint64_t chosen_triangles = 0;
  vk::AccelerationStructure tlas;
  vk::Buffer copy_buffer;
  std::uint64_t copy_count = 0;
  dvec3 anchor{0.0};
  bool rebuilt = false;  // by the last select()
  double build_seconds = 0;

  Impl(const vk::Device& d, const format::Package& package,
       std::function<const vk::AccelerationStructure*(std::uint32_t)> blas)
      : PackageView(package), device(d), p(package), molecule_blas(std::move(blas)) {
    for (const gpu::CompartmentInstance& ci : compartment_instances) {
      instance_first_bit.push_back(total_bits);
      const format::InstanceTransform t = format::instance_transform(ci);
      const gpu::Mesh* m = mesh_of(ci);
      const dvec3 lo = m ? dvec3(m->aabb_min) : dvec3(0.0), hi = m ? dvec3(m->aabb_max) : dvec3(0.0);
      instance_centres.push_back(t.translation + t.linear * (0.5 * (lo + hi)));
      instance_radii.push_back(0.5 * glm::length(hi - lo) * largest_singular_value(t.linear));
      densities.push_back(membrane_density(ci));
      total_bits += m ? m->triangle_count : 0;
    }
    instance_triangles.resize(compartment_instances.size());
    bits.assign(total_bits / 32 + 1, 0u);  // never empty: a storage buffer needs a word
  }

  const gpu::Mesh* mesh_of(const gpu::CompartmentInstance& ci) const {
    if (ci.compartment >= compartments.size() || compartments[ci.compartment].mesh >= meshes.size()) return nullptr;
    return &meshes[compartments[ci.compartment].mesh];
  }

  const std::vector<FlatTriangle>& triangles_of(std::uint32_t i) {
    std::optional<std::vector<FlatTriangle>>& slot = instance_triangles[i];
    if (slot) return *slot;
    slot.emplace();
    const gpu::CompartmentInstance& ci = compartment_instances[i];
    const gpu::Mesh* m = mesh_of(ci);
    if (!m) return *slot;
    const format::InstanceTransform t = format::instance_transform(ci);
    for (std::uint32_t tl = 0; tl < m->triangle_count; ++tl) {
      const std::uint32_t tri = m->first_triangle + tl;
      const gpu::Triangle& v = triangles[tri];
      const dvec3 a = t.translation + t.linear * dvec3(vertex_positions[m->first_vertex + v.v0]);
      const dvec3 b = t.translation + t.linear * dvec3(vertex_positions[m->first_vertex + v.v1]);
      const dvec3 c = t.translation + t.linear * dvec3(vertex_positions[m->first_vertex + v.v2]);
      FlatTriangle f;
      f.centroid = (a + b + c) / 3.0;
      const dvec3 n = glm::cross(b - a, c - a);
      f.area = 0.5 * glm::length(n);
      f.normal = f.area > 0 ? n / (2.0 * f.area) : dvec3(0.0);
      f.radius = std::max({glm::length(a - f.centroid), glm::length(b - f.centroid), glm::length(c - f.centroid)});
      f.owns = tri < triangle_shells.size() && (triangle_shells[tri].h_plus != 0 || triangle_shells[tri].h_minus != 0 || triangle_shells[tri].side_offset != 0);
      slot->push_back(f);
    }
    return *slot;
  }

  // The compartment instance of a bit, and its triangle there.
  std::pair<std::uint32_t, std::uint32_t> locate(std::uint32_t bit) const {
    const auto it = std::upper_bound(instance_first_bit.begin(), instance_first_bit.end(), bit);
    const auto i = std::uint32_t(it - instance_first_bit.begin() - 1);
    return {i, bit - instance_first_bit[i]};
  }

  // Molecules per Wang square (the tile set's mean) over the square's world area (Wang squares are
  // S Å wide in compartment space; the instance scales areas by |det L|^(2/3)).
  double membrane_density(const gpu::CompartmentInstance& ci) const {
    if (ci.compartment >= compartments.size()) return 0;
    const gpu::Compartment& c = compartments[ci.compartment];
    if (c.membrane_recipe == gpu::NANO_NO_INDEX || c.membrane_tile_count == 0 || !(c.scales.y > 0)) return 0;
    // A tile's alternates are shown only in place of a dropped copy: its own copies are the density.
    double molecules = 0;
    for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count && t < tiles2d.size(); ++t)
      for (std::uint64_t i = tiles2d[t].first_instance;
           i < std::uint64_t(tiles2d[t].first_instance) + tiles2d[t].instance_count && i < instances.size(); ++i)
        molecules += (instances[i].flags & gpu::NANO_INSTANCE_ALTERNATE) == 0u ? 1.0 : 0.0;
    const double area_scale = std::pow(std::abs(glm::determinant(format::instance_transform(ci).linear)), 2.0 / 3.0);
    return molecules / c.membrane_tile_count / (double(c.scales.y) * c.scales.y * area_scale);
  }

  std::uint64_t bytes_for(std::uint64_t count) const {
    if (count == 0) return 0;
    return vk::top_level_size(device, std::uint32_t(std::min(count, kCopyLimit))) + count * sizeof(gpu::FlatCopy);
  }

  // The most copies a level within `budget` bytes can hold.
  std::uint64_t capacity(std::uint64_t budget) const {
    std::uint64_t lo = 0, hi = std::min(kCopyLimit - 1, budget / sizeof(gpu::FlatCopy));
    while (lo < hi) {
      const std::uint64_t mid = lo + (hi - lo + 1) / 2;
      if (bytes_for(mid) <= budget) lo = mid; else hi = mid - 1;
    }
    return lo;
  }

  // The copies (with atoms) triangle `bit` owns, enumerated once.
  const std::vector<Placed>& copies_of(std::uint32_t bit) {
    if (const auto it = cache.find(bit); it != cache.end()) return it->second;
    std::vector<Placed>& slot = cache[bit];
    const auto [instance, local] = locate(bit);
    if (!triangles_of(instance)[local].owns) return slot;
    if (!enumerator) enumerator = std::make_unique<placement::CopyEnumerator>(p);
    enumerator->for_each_membrane_copy(instance, local, [&](const placement::Copy& c) {
      if (c.molecule_type >= molecules.size() || !molecule_blas(c.molecule_type)) return;  // nothing to hit
      gpu::FlatCopy r{};
      r.compartment_instance = c.id.compartment_instance;
      r.element = c.id.element;
      r.kind = std::uint32_t(c.id.kind);
      r.instance = c.id.instance;
      r.cell = glm::ivec4(c.id.cell, 0);
      r.number_lo = std::uint32_t(c.number);
      r.number_hi = std::uint32_t(c.number >> 32);
      r.molecule_type = c.molecule_type;
      slot.push_back({c.origin, glm::mat3(c.linear), float(c.radius), r});
    });
    // Along a Morton curve within the triangle once, so a rebuild only orders the triangles.
    std::vector<VkAabbPositionsKHR> bounds;
    for (const Placed& c : slot) bounds.push_back(ball_box(c.origin, c.radius, slot.front().origin));
    std::vector<Placed> sorted;
    sorted.reserve(slot.size());
    for (const std::uint32_t k : morton_order(bounds)) sorted.push_back(slot[k]);
    slot = std::move(sorted);
    cached_copies += slot.size();
    return slot;
  }

  // What flattening triangle f saves per Å², in pixels (0: outside the view): the pixels a patch at
  // its centroid would cover facing the eye. Not its projected area: a grazing patch covers fewer
  // pixels, but each of their rays crosses more overlapping prisms, which is what the virtual path
  // pays for. A quarter of it for a patch facing away (seen only through the gaps of the near side,
  // unless clipping opens the membrane: `both_sides`).
  double pixels_per_area(const FlatTriangle& f, const gpu::Camera& camera, bool both_sides) const {
    const dvec3 to = f.centroid - dvec3(vec3(camera.position));
    const double d = glm::length(to);
    if (!(d > f.radius)) return std::numeric_limits<double>::infinity();  // the eye is at the triangle
    if (!in_view(to, f.radius, camera)) return 0;
    const double facing = -glm::dot(f.normal, to) / d;
    const double hidden = facing < 0 && !both_sides ? 0.25 : 1.0;
    return hidden * pixels_per_radian_squared(camera) / (d * d);
  }

  static double pixels_per_radian_squared(const gpu::Camera& camera) {
    const double ppr = double(camera.size.y) / (2.0 * camera.forward.w);
    return ppr * ppr;
  }

  // True iff a ball of `radius` at `to` from the eye may meet the view's pyramid (a cone test per
  // image axis, widened by the ball's angular radius).
  static bool in_view(const dvec3& to, double radius, const gpu::Camera& camera) {
    const double z = glm::dot(to, dvec3(vec3(camera.forward)));
    if (z <= -radius) return false;  // behind the eye
    const double tan_half = camera.forward.w, aspect = camera.right.w, slack = radius / std::max(z, radius);
    if (std::abs(glm::dot(to, dvec3(vec3(camera.right)))) / std::max(z, 1e-9) > tan_half * aspect + slack) return false;
    return std::abs(glm::dot(to, dvec3(vec3(camera.up)))) / std::max(z, 1e-9) <= tan_half + slack;
  }

  bool select(const gpu::Camera& camera, std::uint64_t budget, bool both_sides, std::uint64_t new_copies) {
    const dvec3 eye(vec3(camera.position));
    if (budget > 0 && (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z) || camera.size.y == 0 ||
                       !(camera.forward.w > 0)))
      throw std::invalid_argument("FlatLevel::select: a camera with a finite eye, a field of view and an image");
    std::vector<std::uint32_t> choice;
    if (budget != capacity_budget) capacity_budget = budget, capacity_copies = budget > 0 ? capacity(budget) : 0;
    const std::uint64_t room = capacity_copies;
    if (room > 0) {
      // Most pixels per Å² first (copies follow area), each taken while its copies cover enough
      // pixels to pay and the level has room: the nearest triangles in view, facing ones first.
      std::vector<std::pair<double, std::uint32_t>> order;  // a max-heap: usually few are taken
      for (std::uint32_t i = 0; i < compartment_instances.size(); ++i) {
        // Whole instances out of view, or too far for any of their triangles to pay, are skipped.
        const dvec3 to = instance_centres[i] - eye;
        const double gap = std::max(glm::length(to) - instance_radii[i], 1e-9);
        if (!(densities[i] > 0) || !in_view(to, instance_radii[i], camera) ||
            pixels_per_radian_squared(camera) / (gap * gap) < kMinPixelsPerCopy * densities[i])
          continue;
        const std::vector<FlatTriangle>& tris = triangles_of(i);
        for (std::uint32_t tl = 0; tl < tris.size(); ++tl)
          if (tris[tl].owns)
            if (const double s = pixels_per_area(tris[tl], camera, both_sides); s > 0)
              order.push_back({s, instance_first_bit[i] + tl});
      }
      std::make_heap(order.begin(), order.end());
      std::uint64_t used = 0, enumerated = 0;
      for (auto end = order.end(); end != order.begin(); --end) {
        std::pop_heap(order.begin(), end);
        const auto [score, b] = *(end - 1);
        // Judged first by its instance's mean copies per Å² (an enumeration costs about what the
        // placement does on the device), then by its own copies. Neither depends on what earlier
        // calls enumerated: unbounded, the choice is a function of the camera and the budget (a movie's
        // frames equal single renders).
        const auto [instance, local] = locate(b);
        if (score < kMinPixelsPerCopy * densities[instance]) break;
        const bool fresh = !cache.count(b);
        if (fresh && enumerated >= new_copies) break;  // the rest on later calls
        const std::uint64_t n = copies_of(b).size();
        if (fresh) enumerated += n + 1;
        if (n == 0) continue;
        if (score * triangles_of(instance)[local].area < kMinPixelsPerCopy * double(n)) break;  // later ones pay less still
        if (used + n > room) break;
        choice.push_back(b);
        used += n;
      }
      std::sort(choice.begin(), choice.end());
    }
    // Host memory: forget enumerated triangles the choice does not hold once they outgrow it.
    if (cached_copies > 4 * room + 100'000) {
      for (auto it = cache.begin(); it != cache.end();) {
        if (std::binary_search(choice.begin(), choice.end(), it->first)) {
          ++it;
          continue;
        }
        cached_copies -= it->second.size();
        it = cache.erase(it);
      }
    }
    const bool changed = choice != chosen;
    if (changed) chosen = std::move(choice);
    rebuilt = changed || (copy_count > 0 && eye != anchor);
    if (rebuilt) rebuild(eye);
    return changed;
  }

  // The level over the chosen triangles' copies relative to the eye, Morton-sorted (the TLAS build
  // splits in input order): the triangles along a Morton curve of their centroids, each one's copies
  // in the order copies_of gave them. Relative to the eye as the µLAS is: the hardware forms each
  // copy's object-space ray origin from a float transform whose translation is the copy's distance
  // from the eye, so a copy 10 Å away is placed to ~10⁻⁶ Å (an anchor 10⁴ Å away cost 10⁻³ Å: a
  // pixel in 10⁵ of blood's closest view grazed another atom than the oracle). Run at every new eye
  // of an orbit, so it is lean: one submission (the copy records' upload rides with the build) and
  // the instance records written where the build reads them.
  void rebuild(const dvec3& eye) {
    tlas = {};
    copy_buffer = {};
    copy_count = 0;
    chosen_triangles = 0;
    std::fill(bits.begin(), bits.end(), 0u);
    std::vector<VkAabbPositionsKHR> triangle_bounds;
    std::uint64_t count = 0;
    for (const std::uint32_t b : chosen) {
      bits[b >> 5] |= 1u << (b & 31u);
      ++chosen_triangles;
      const auto [instance, local] = locate(b);
      const FlatTriangle& f = triangles_of(instance)[local];
      triangle_bounds.push_back(ball_box(f.centroid, f.radius, eye));
      count += cache.at(b).size();
    }
    if (count == 0) return;
    anchor = eye;
    std::vector<VkAccelerationStructureInstanceKHR> instances;
    std::vector<gpu::FlatCopy> records;
    instances.reserve(count);
    records.reserve(count);
    for (const std::uint32_t t : morton_order(triangle_bounds))
      for (const Placed& c : cache.at(chosen[t])) {
        glm::dmat4 m(glm::dmat3(c.linear));
        m[3] = glm::dvec4(c.origin - anchor, 1.0);
        instances.push_back(vk::make_instance(*molecule_blas(c.record.molecule_type), m, std::uint32_t(records.size())));
        records.push_back(c.record);
      }
    // Build input and staging in host-visible memory, freed once the build has read them.
    const vk::Buffer input = vk::Buffer::with_data(device, std::as_bytes(std::span(instances)), vk::kBuildInputUsage,
                                                   vk::MemoryUse::HostVisible);
    const vk::Buffer staging = vk::Buffer::with_data(device, std::as_bytes(std::span(records)),
                                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::HostVisible);
    copy_buffer = vk::Buffer(device, staging.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             vk::MemoryUse::DeviceLocal);
    tlas = vk::build_top_level(device, input.address(), std::uint32_t(instances.size()),
                               [&](VkCommandBuffer commands) { vk::Buffer::record_copy(commands, staging, copy_buffer); });
    copy_count = records.size();
  }
};

FlatLevel::FlatLevel(const vk::Device& device, const format::Package& package,
                     std::function<const vk::AccelerationStructure*(std::uint32_t)> molecule_blas)
    : impl_(std::make_unique<Impl>(device, package, std::move(molecule_blas))) {}
FlatLevel::~FlatLevel() = default;
FlatLevel::FlatLevel(FlatLevel&&) noexcept = default;

bool FlatLevel::select(const gpu::Camera& camera, std::uint64_t budget_bytes, bool both_sides, std::uint64_t new_copies) {
  const auto start = std::chrono::steady_clock::now();
  const bool changed = impl_->select(camera, budget_bytes, both_sides, new_copies);
  if (impl_->rebuilt) impl_->build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return changed;
}
std::uint32_t FlatLevel::first_bit(std::uint32_t instance) const {
  if (instance >= impl_->instance_first_bit.size()) throw std::out_of_range("FlatLevel::first_bit: no such compartment instance");
  return impl_->instance_first_bit[instance];
}
bool FlatLevel::flattened(std::uint32_t instance, std::uint32_t triangle) const {
  if (instance >= impl_->instance_first_bit.size()) return false;
  const std::uint64_t b = std::uint64_t{impl_->instance_first_bit[instance]} + triangle;
  const std::uint64_t end = instance + 1 < impl_->instance_first_bit.size() ? impl_->instance_first_bit[instance + 1] : impl_->total_bits;
  return b < end && std::binary_search(impl_->chosen.begin(), impl_->chosen.end(), std::uint32_t(b));
}
const std::vector<std::uint32_t>& FlatLevel::triangle_bits() const { return impl_->bits; }
std::uint64_t FlatLevel::triangles() const { return impl_->chosen_triangles; }
bool FlatLevel::empty() const { return impl_->copy_count == 0; }
glm::dvec3 FlatLevel::anchor() const { return impl_->anchor; }
std::uint64_t FlatLevel::copies() const { return impl_->copy_count; }
std::uint64_t FlatLevel::memory_bytes() const { return empty() ? 0 : impl_->tlas.size() + impl_->copy_buffer.size(); }
double FlatLevel::last_build_seconds() const { return impl_->build_seconds; }
const vk::AccelerationStructure& FlatLevel::tlas() const {
  if (empty()) throw std::logic_error("FlatLevel::tlas: the level is empty");
  return impl_->tlas;
}
const vk::Buffer& FlatLevel::copy_records() const {
  if (empty()) throw std::logic_error("FlatLevel::copy_records: the level is empty");
  return impl_->copy_buffer;
}

}  // namespace nano::render
