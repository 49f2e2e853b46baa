#pragma once
// What each core-grid BOUNDARY box keeps (render_scene.h KeptBox, binding NANO_B_KEPT_BOXES): the
// union of the boxes of the molecules its keep-mask keeps, as the cube's mLAS holds them. Near a
// membrane those molecules fill one side of the box, so a ray that meets the box's reach only on
// the other side (often before the membrane's own hit) skips the mLAS query there.
#include <span>
#include <vector>

#include "format/package_view.hpp"
#include "shared/render_scene.h"

namespace nano::render {

// One record per record of section boundary_boxes, in the box's frame (core_box_min at the origin):
// each kept molecule's position ± (type_radius[its type] + 0.01 Å), the same widening as the cube's
// mLAS boxes, rounded one ulp outward; lo.w = 1, or a zero record (lo.w = 0) when the mask keeps
// nothing. `view` must have passed format::validate_semantics.
std::vector<gpu::KeptBox> kept_boxes(const format::PackageView& view, std::span<const double> type_radius);

}  // namespace nano::render
