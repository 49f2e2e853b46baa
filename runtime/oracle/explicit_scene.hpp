#pragma once
// The explicit-instancing oracle: every molecule copy of a package whose atoms can reach a
// world-space box, and every atom inside it, evaluated on the CPU from docs/placement.md with the
// shaders' own placement functions (shaders/shared/, compiled as C++). `nanoview export` writes its
// atoms and `nanoview verify` compares the GPU against it, so it trusts as little of the package as
// it can: bounding radii come from the atoms themselves, and culling never relies on the triangle
// shells or the mesh AABB (checking those is part of what verify is for).
//
// The copies come from nano::placement::CopyEnumerator (runtime/placement/), which the flat level
// uses too; this adds the atoms.
//
// Precision: each copy's compartment-space placement is the float Affine3 of
// chart_membrane_molecule / core_soluble_molecule, exactly as a shader computes it; atoms and the
// compartment instance transform are then applied in double.
//
// Streaming: copies and atoms go to a callback as they are computed, nothing is materialised.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "format/package.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/copy_enumerator.hpp"

namespace nano::oracle {

using placement::Copy;
using placement::CopyId;
using placement::CopyKind;
using placement::WorldBox;
using ExplicitSceneOptions = placement::CopyOptions;

struct AtomSample {
  const Copy* copy = nullptr;
  std::uint32_t atom = 0;                     // index into section atoms
  const format::AtomInfo* info = nullptr;     // nullptr when the package has no atom_info
  glm::dvec3 position{0.0};                   // world, Å
  double radius = 0.0;                        // atom radius times Copy::stretch
};

class ExplicitScene {
public:
  // `package` must have passed format::validate_semantics and must outlive this object. Throws
  // what placement::CopyEnumerator throws.
  explicit ExplicitScene(const format::Package& package, const ExplicitSceneOptions& options = {});
  ~ExplicitScene();
  ExplicitScene(ExplicitScene&&) noexcept;

  // Copies as placement::CopyEnumerator hands them (the Copy is only valid during the call).
  void for_each_copy(const WorldBox& box, const std::function<void(const Copy&)>& visit) const;
  void for_each_copy_of(std::uint32_t instance, const WorldBox& box, const std::function<void(const Copy&)>& visit) const;
  void for_each_membrane_copy(std::uint32_t instance, std::uint32_t triangle, const std::function<void(const Copy&)>& visit) const;
  // The medium's kept copies of region box `box` (placement::CopyEnumerator::for_each_medium_copy).
  bool has_medium() const;
  void for_each_medium_copy(const glm::ivec3& box, const std::function<void(const Copy&)>& visit,
                            const placement::CopyEnumerator::SphereTest& may_meet = {}) const;
  // Every atom whose centre lies in `box`; atoms of a copy are consecutive, in the type's order.
  // The medium's atoms come last; a box spanning more than `max_medium_boxes` of its region boxes
  // is refused (InputError): they would hold billions of copies.
  void for_each_atom(const WorldBox& box, const std::function<void(const AtomSample&)>& visit,
                     std::uint64_t max_medium_boxes = 4'000'000) const;
  // The same without the medium (the oracle's rounds trace it apart, along each ray).
  void for_each_compartment_atom(const WorldBox& box, const std::function<void(const AtomSample&)>& visit) const;

  // Copy numbers lie in [0, copy_number_limit()).
  std::uint64_t copy_number_limit() const;
  // Where each compartment instance stands (the package's transforms unless the options moved them).
  const std::vector<format::InstanceTransform>& instance_transforms() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::oracle
