#pragma once
#include <span>

#include <glm/vec4.hpp>
// Judges one differing pixel of `verify` against the explicit scene itself: is there a change of
// every atom's radius, each on its own within a relative ±ε, that makes the first hit along the
// pixel's ray the one the device reports? Unlike re-rendering with every radius scaled by one
// factor (render_compare.hpp), it covers two grazing touches on one ray, one shrunk and one grown
// (measured: a ray through a mesh vertex grazing a lipid atom at 1e-6 Å and a haemoglobin atom
// behind it at 3e-5 Å).
#include <glm/vec3.hpp>

#include "runtime/oracle/explicit_scene.hpp"
#include "shared/camera.h"

namespace nano::oracle {

// True when, with radii r·(1 ± epsilon) chosen per atom:
//  * `test` is the background and no atom along the ray (t > 0, up to leaving `bounds`) is entered
//    even when shrunk; or
//  * `test` names an atom (copy number and atom index) that the ray meets within its grown radius,
//    at a depth between its grown entry and its shrunk entry (its tangent point when shrinking
//    loses it), ± depth_tolerance, and no other atom is entered in front of that depth even when
//    shrunk.
// Never true when an atom meeting the ray is entered at t <= 0 (the eye inside or on it): the
// device and the oracle may then disagree on what a hit means, and that is not a radius question.
// `largest_atom`: the largest atom radius of the package (Å), bounding the search around the ray.
// `medium_ulps`: float steps, at a medium atom's distance from the eye, by which that atom may stand
// apart on the device, which places the medium relative to the eye's box in float (a 0.008 Å step
// at 8·10^4 Å, where a pixel spans hundreds of Å); its radius is widened by that much both ways.
bool explained_by_atom_radii(const ExplicitScene& scene, const WorldBox& bounds, const glm::dvec3& eye,
                             const glm::dvec3& direction, const gpu::PixelHit& test, double epsilon,
                             double largest_atom, std::span<const glm::dvec4> clip = {}, double medium_ulps = 0);

// True when the device's atom (`test`) and the oracle's (`reference`) are both met by the ray, in
// the explicit scene, at the depth each reports, and those depths agree within depth_tolerance: two
// atom surfaces crossing the ray at one point (to 10⁻³ Å), which the device's float placement may
// order either way. A ray starting inside a sphere meets it where it leaves it (the oracle's rule),
// so this also judges the views whose eye stands inside an atom.
bool explained_as_tie(const ExplicitScene& scene, const glm::dvec3& eye, const glm::dvec3& direction,
                      const gpu::PixelHit& test, const gpu::PixelHit& reference, double largest_atom);

// True when `test` names an atom the ray meets, in the explicit scene, at a depth its sphere gives
// with its centre moved by at most `slack` Å: the device places copies in float (a few float steps
// at the scene's largest coordinate), and a small shift of a sphere moves its entry by more than the
// shift where the ray meets it obliquely. No claim for an eye within reach of the atom.
bool explained_by_placement(const ExplicitScene& scene, const glm::dvec3& eye, const glm::dvec3& direction,
                            const gpu::PixelHit& test, double slack, double largest_atom);

}  // namespace nano::oracle
