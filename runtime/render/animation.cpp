#include "common/effect_table.hpp"
#include "runtime/render/animation.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace nano::render {
namespace {

using glm::dmat3;
using glm::dvec3;

format::InstanceTransform from_record(const glm::vec4 (&rows)[3]) {
  gpu::CompartmentInstance ci{};
  for (int r = 0; r < 3; ++r) ci.transform[r] = rows[r];
  return format::instance_transform(ci);
}

// linear = R·diag(scale) with R a rotation (a mirror goes into a negative first scale).
void split(const dmat3& linear, glm::dquat& rotation, dvec3& scale) {
  dmat3 r;
  for (int c = 0; c < 3; ++c) {
    scale[c] = glm::length(linear[c]);
    r[c] = linear[c] / scale[c];
  }
  if (glm::determinant(r) < 0) {
    scale.x = -scale.x;
    r[0] = -r[0];
  }
  rotation = glm::normalize(glm::quat_cast(r));
}

}  // namespace

format::InstanceTransform interpolate_transform(const format::InstanceTransform& a, const format::InstanceTransform& b,
                                                double s) {
  if (s <= 0) return a;
  if (s >= 1) return b;
  glm::dquat qa, qb;
  dvec3 sa, sb;
  split(a.linear, qa, sa);
  split(b.linear, qb, sb);
  format::InstanceTransform t;
  const dmat3 r = glm::mat3_cast(glm::slerp(qa, qb, s));
  const dvec3 scale = glm::mix(sa, sb, s);
  for (int c = 0; c < 3; ++c) t.linear[c] = r[c] * scale[c];
  t.translation = glm::mix(a.translation, b.translation, s);
  return t;
}

std::vector<format::InstanceTransform> animated_instance_transforms(const format::Package& package, double time) {
  using format::SectionKind;
  const auto instances = package.records<SectionKind::compartment_instances>();
  std::vector<format::InstanceTransform> out;
  out.reserve(instances.size());
  for (const gpu::CompartmentInstance& ci : instances) out.push_back(format::instance_transform(ci));
  const std::uint32_t flags =
      package.record_count(SectionKind::scene) == 1 ? package.records<SectionKind::scene>()[0].effect_flags : 0u;
  if (!(flags & package_flag(EffectId::animation)) || package.record_count(SectionKind::effects) != 1) return out;

  const auto keys = package.records<SectionKind::keyframes>();
  if (!keys.empty()) {
    // Ascending (instance, time), as the validator guarantees.
    for (std::size_t first = 0; first < keys.size();) {
      std::size_t end = first;
      while (end < keys.size() && keys[end].instance == keys[first].instance) ++end;
      const std::uint32_t i = keys[first].instance;
      const auto after = std::upper_bound(keys.begin() + first, keys.begin() + end, time,
                                          [](double t, const gpu::InstanceKeyframe& k) { return t < k.time; });
      if (after == keys.begin() + first) out[i] = from_record(keys[first].transform);
      else if (after == keys.begin() + end) out[i] = from_record(keys[end - 1].transform);
      else {
        const gpu::InstanceKeyframe& k0 = *(after - 1);
        const gpu::InstanceKeyframe& k1 = *after;
        out[i] = interpolate_transform(from_record(k0.transform), from_record(k1.transform),
                                       (time - k0.time) / (double(k1.time) - double(k0.time)));
      }
      first = end;
    }
    return out;
  }

  const gpu::SceneEffects& e = package.records<SectionKind::effects>()[0];
  const dmat3 spin = e.spin.w != 0.f
                         ? glm::mat3_cast(glm::angleAxis(glm::radians(double(e.spin.w) * time), glm::normalize(dvec3(e.spin))))
                         : dmat3(1.0);
  for (format::InstanceTransform& t : out) {
    t.linear = spin * t.linear;
    t.translation += dvec3(e.velocity) * time;
  }
  return out;
}

}  // namespace nano::render
