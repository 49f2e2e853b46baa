#include "runtime/placement/medium_rule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "common/singular_value.hpp"

namespace nano::placement {

std::vector<gpu::MediumInstance> medium_instances(const format::PackageView& p,
                                                  std::span<const format::InstanceTransform> transforms) {
  const glm::dvec3 region_min(p.medium[0].region_min);
  std::vector<gpu::MediumInstance> out;
  out.reserve(transforms.size());
  for (std::size_t i = 0; i < transforms.size(); ++i) {
    const format::InstanceTransform& t = transforms[i];
    // compartment = L⁻¹(world − T) = L⁻¹·p + L⁻¹(region_min − T).
    const glm::dmat3 inverse = glm::inverse(t.linear);
    const glm::dvec3 offset = inverse * (region_min - t.translation);
    gpu::MediumInstance m{};
    glm::vec4* rows[3] = {&m.row0, &m.row1, &m.row2};
    for (int r = 0; r < 3; ++r) *rows[r] = glm::vec4(float(inverse[0][r]), float(inverse[1][r]), float(inverse[2][r]), float(offset[r]));
    // The least singular value of L: 1 / the largest of L⁻¹ (1 exactly for a rigid instance).
    m.stretch = glm::vec4(float(1.0 / largest_singular_value(inverse)), 0.0f, 0.0f, 0.0f);
    m.ids = glm::uvec4(p.compartment_instances[i].compartment, 0u, 0u, 0u);
    out.push_back(m);
  }
  return out;
}

std::pair<glm::dvec3, glm::dvec3> exclusion_box(const gpu::ExclusionField& f, const format::InstanceTransform& t,
                                                const glm::dvec3& region_min) {
  const glm::dvec3 lo(f.origin), hi = lo + double(f.origin.w) * (glm::dvec3(glm::uvec3(f.dims)) - 1.0);
  glm::dvec3 box_lo(std::numeric_limits<double>::infinity()), box_hi(-std::numeric_limits<double>::infinity());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 q((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    const glm::dvec3 w = t.linear * q + t.translation - region_min;
    box_lo = glm::min(box_lo, w), box_hi = glm::max(box_hi, w);
  }
  return {box_lo - 1.0, box_hi + 1.0};
}

float exclusion_value(const format::PackageView& p, const gpu::MediumInstance& m, const glm::vec3& c) {
  const gpu::ExclusionField& f = p.exclusion_fields[m.ids.x];
  glm::ivec3 cell;
  glm::vec3 frac;
  if (!gpu::exclusion_cell(f, gpu::medium_to_compartment(m, c), cell, frac)) return f.limits.y;
  float corners[8];
  for (int k = 0; k < 8; ++k)
    corners[k] = p.exclusion_values[gpu::exclusion_node(f, cell + glm::ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1))];
  return gpu::exclusion_trilinear(corners, frac);
}

bool medium_copy_kept(const format::PackageView& p, std::span<const gpu::MediumInstance> instances,
                      std::span<const std::uint32_t> near, const glm::vec3& c, float r) {
  const float clearance = p.medium[0].region_max.w;
  for (const std::uint32_t i : near) {
    const gpu::MediumInstance& m = instances[i];
    if (!gpu::medium_copy_clear(exclusion_value(p, m, c), p.exclusion_fields[m.ids.x], m.stretch.x, r, clearance)) return false;
  }
  return true;
}

}  // namespace nano::placement
