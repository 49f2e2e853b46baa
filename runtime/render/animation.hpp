#pragma once
// Proxy animation (paper §5.4): where the compartment instances stand at a time, as the package's
// effects say. Only the µLAS — one instance record per compartment instance — is rebuilt from
// these transforms each frame; the mLAS and nLAS never change.
#include <vector>

#include "format/package.hpp"
#include "format/package_view.hpp"

namespace nano::render {

// The transform of every compartment instance at `time` (seconds):
// - keyframes (section "keyframes"): per instance, translation interpolated linearly, rotation by
//   slerp, per-axis scale linearly between the two keys around `time`; held before the first and
//   after the last key; instances without keys stay where the package puts them;
// - steady motion (section "effects", no keyframes): each instance turns about the world axis through
//   its own origin by spin·time and drifts by velocity·time;
// - no animation in the package: the package's transforms.
std::vector<format::InstanceTransform> animated_instance_transforms(const format::Package& package, double time);

// Interpolates two affine transforms as described above (s in [0, 1]); exact at s = 0 and 1 for
// rotations with positive scales.
format::InstanceTransform interpolate_transform(const format::InstanceTransform& a, const format::InstanceTransform& b,
                                                double s);

}  // namespace nano::render
