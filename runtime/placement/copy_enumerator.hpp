#pragma once
// Every molecule copy of a package whose atoms can reach a world-space box, placed on the CPU from
// docs/placement.md with the shaders' own placement functions (shaders/shared/, compiled as C++).
// Two users that must not depend on each other enumerate copies with it: the CPU oracle
// (runtime/oracle/: `nanoview export` and `verify`'s reference) and the flat level
// (runtime/render/flat_level.cpp), so the renderer does not link the oracle. It trusts as little of
// the package as it can: bounding radii come from the atoms themselves, and culling never relies
// on the triangle shells or the mesh AABB (checking those is part of what verify is for).
//
// Precision: each copy's compartment-space placement is the float Affine3 of
// chart_membrane_molecule / core_soluble_molecule, exactly as a shader computes it; the
// compartment instance transform is then applied in double.
//
// Streaming: copies go to a callback as they are computed, nothing is materialised.
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "format/package.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/visibility.hpp"

namespace nano::placement {

// Closed world-space box [min, max] (Å). Infinite bounds are allowed: everything() disables culling.
struct WorldBox {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};

  static WorldBox everything() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {glm::dvec3(-inf), glm::dvec3(inf)};
  }
  bool contains(const glm::dvec3& p) const {
    return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x <= max.x && p.y <= max.y && p.z <= max.z;
  }
  // True iff the closed ball (centre, radius) meets the box.
  bool meets_sphere(const glm::dvec3& centre, double radius) const;
};

enum class CopyKind : std::uint8_t { membrane = 0, core = 1, medium = 2 };

// The identity of a copy as docs/placement.md names it.
struct CopyId {
  std::uint32_t compartment_instance = 0;
  CopyKind kind = CopyKind::membrane;
  std::uint32_t element = 0;    // membrane: triangle (index into section triangles); core, medium: box linear index
  glm::ivec3 cell{0};           // membrane: tile cell (a, b, 0); core, medium: box (i, j, k)
  std::uint32_t instance = 0;   // index of the molecule within its Wang square / cube (0-based)
};

struct Copy {
  CopyId id;
  // Compact unique number, decodable back into the id (CopyEnumerator::copy_number_limit):
  //   base(instance) + (t_local·W·H + slot)·I₂ + instance   for membrane copies,
  //   base(instance) + T·W·H·I₂ + box·I₃ + instance         for core copies,
  //   (every instance's range) + box·I_medium + instance    for medium copies (compartment_instance
  //                                                          then names no instance: NANO_MEDIUM_OWNER),
  // with T the mesh's triangle count, slot = (a − origin_a) + W·(b − origin_b) in the triangle's
  // replication area, I₂ / I₃ the largest instance count of the compartment's squares / cubes, and
  // base the prefix sum of those ranges over the compartment instances.
  std::uint64_t number = 0;
  std::uint32_t molecule_type = 0;
  glm::dmat3 linear{1.0};  // molecule space -> world, linear part (rotation · instance linear part)
  glm::dvec3 origin{0.0};  // world position of the molecule's origin
  double stretch = 1.0;     // largest singular value of the instance's linear part (1 when rigid)
  double radius = 0.0;      // world bounding radius: max over atoms of |centre| + radius, times stretch
};

// What the scene's effects change in the copies (runtime/render/effects.hpp): instances moved by
// animation, and protein jitter with the shader's own function (shared/effects.h) on the same floats.
struct CopyOptions {
  std::vector<format::InstanceTransform> instance_transforms;  // empty: the package's; else one per instance
  bool jitter = false;
  glm::vec3 jitter_parameters{0.0f};  // time (s), amplitude (radians), frequency (Hz), as the frame holds them
  // Clipping half-spaces (unit n, d), world Å: copies, core boxes and membrane triangles whose
  // every atom centre lies outside one of them are skipped (an oracle view behind a clip plane
  // would otherwise enumerate everything it removes). Atoms are still judged one by one by the caller.
  std::vector<glm::dvec4> clip;
  // The scene's medium is part of the picture (false: `--hide medium`, has_medium() says no).
  bool medium = true;
  // Compartments and molecule types left out (--hide): their copies are never visited, while a
  // hidden compartment still keeps the medium out of its place.
  Visibility visibility;
};

class CopyEnumerator {
public:
  // `package` must have passed format::validate_semantics and must outlive this object. Throws
  // nano::InputError for what the validator does not check but placement needs (UVs off the 2^-24
  // grid or |uv| ≥ 16, a triangle needing more than W×H tiles, tile or cube sizes that differ
  // from the compartment's, a singular instance transform, copy numbers beyond 64 bits).
  explicit CopyEnumerator(const format::Package& package, const CopyOptions& options = {});
  ~CopyEnumerator();
  CopyEnumerator(CopyEnumerator&&) noexcept;

  // The Copy handed to `visit` is only valid during the call (one object is reused).
  // Every copy whose bounding sphere meets `box`, each once, in a deterministic order (compartment
  // instance, membrane triangles then core boxes; BOUNDARY boxes yield the molecules their
  // keep-mask keeps).
  void for_each_copy(const WorldBox& box, const std::function<void(const Copy&)>& visit) const;
  // The same for compartment instance `instance` alone (std::out_of_range beyond the last).
  void for_each_copy_of(std::uint32_t instance, const WorldBox& box, const std::function<void(const Copy&)>& visit) const;
  // The membrane copies local triangle `triangle` of compartment instance `instance` owns (none
  // beyond the mesh's last triangle), in for_each_copy's order.
  void for_each_membrane_copy(std::uint32_t instance, std::uint32_t triangle, const std::function<void(const Copy&)>& visit) const;

  // The medium (shaders/shared/medium.h; not part of for_each_copy, whose boxes would hold
  // billions of its copies): the copies of region box `box` that its keep rule keeps, none beyond
  // the region or without a medium; and the ones whose sphere meets `box`, refusing (InputError)
  // a box of more than `max_boxes` region boxes. A copy whose bounding sphere (origin, radius, as the
  // Copy will hold them) misses `cull` or fails `may_meet` is passed over before its keep test, the
  // costly part: `visit` sees the copies it would see if it rejected those itself.
  bool has_medium() const;
  using SphereTest = std::function<bool(const glm::dvec3& origin, double radius)>;
  void for_each_medium_copy(const glm::ivec3& box, const WorldBox& cull, const std::function<void(const Copy&)>& visit,
                            const SphereTest& may_meet = {}) const;
  void for_each_medium_copy(const WorldBox& box, const std::function<void(const Copy&)>& visit,
                            std::uint64_t max_boxes = 100'000'000) const;

  // Copy numbers lie in [0, copy_number_limit()).
  std::uint64_t copy_number_limit() const;
  // Where each compartment instance stands (the package's transforms unless the options moved them).
  const std::vector<format::InstanceTransform>& instance_transforms() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::placement
