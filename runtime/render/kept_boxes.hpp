#pragma once
// What each core-grid BOUNDARY box keeps (binding NANO_B_KEPT_BOXES, one word a record: render_scene.h
// kept_box_unpack): a box around the molecules its keep-mask keeps, as the cube's mLAS holds them.
// Near a membrane those molecules fill one side of the box, so a ray that meets the box's reach only
// on the other side (often before the membrane's own hit) skips the mLAS query there.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "format/package_view.hpp"

namespace nano::render {

// The word for a kept box [lo, hi] (box frame, Å) of boxes of edge B: the smallest box of the
// 31-step grid over [−B, 2B] that holds it once kept_box_unpack decodes it in float (clamped to the
// grid's ends), with NANO_KEPT_ANY set.
std::uint32_t kept_box_pack(const glm::dvec3& lo, const glm::dvec3& hi, float B);

// One word per record of section boundary_boxes: each kept molecule's position ± (type_radius[its
// type] + 0.01 Å), the same widening as the cube's mLAS boxes; 0 when the mask keeps nothing. `view`
// must have passed format::validate_semantics.
std::vector<std::uint32_t> kept_boxes(const format::PackageView& view, std::span<const double> type_radius);

}  // namespace nano::render
