#pragma once
// The medium's per-instance records and keep rule on the CPU (shaders/shared/medium.h): the
// renderer uploads medium_instances() and boxes its exclusion structure with exclusion_box(); the
// CPU oracle decides each copy with medium_copy_kept(), the same float functions the shader runs.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "format/package_view.hpp"
#include "shaders/shared/medium.h"

namespace nano::placement {

// One record per compartment instance: region space (world − region_min) → compartment space,
// computed in double from `transforms` (one per instance). Requires a medium.
std::vector<gpu::MediumInstance> medium_instances(const format::PackageView& p,
                                                  std::span<const format::InstanceTransform> transforms);

// The region-space box holding instance `t`'s exclusion field grid, grown by 1 Å: a copy whose
// centre lies outside it is beyond the field, clear of that instance.
std::pair<glm::dvec3, glm::dvec3> exclusion_box(const gpu::ExclusionField& f, const format::InstanceTransform& t,
                                                const glm::dvec3& region_min);

// The field's interpolated value at region-space point c for one instance, or its clamp beyond the grid.
float exclusion_value(const format::PackageView& p, const gpu::MediumInstance& m, const glm::vec3& c);

// A medium copy centred at region-space c (medium_copy_centre) with world radius r is kept iff no
// instance's field says otherwise. `near` lists the instances whose exclusion_box holds c (the
// caller's cull; testing every instance decides the same).
bool medium_copy_kept(const format::PackageView& p, std::span<const gpu::MediumInstance> instances,
                      std::span<const std::uint32_t> near, const glm::vec3& c, float r);

}  // namespace nano::placement
