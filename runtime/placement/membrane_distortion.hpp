#pragma once
// How far a membrane molecule's true placement (chart_membrane_molecule: the interpolated normal
// n(uv_m) and the frame built on it, not M1's face frame) can stray from where M1 puts it: the
// renderer's Wang-square mLAS boxes are widened by it so that they hold every copy wherever a
// triangle places it (docs/rendering.md). Pure geometry over the shaders' placement math
// (shaders/shared/tile_mapper.h): no package, no Vulkan; tests/placement checks the boxes against
// the placement itself.
//
// In tile space (M1⁻¹) an atom offset p of a copy becomes T·p with T = L·F, L the inverse linear part
// of M1 and F the copy's frame; its centre (x, y, z) moves by z·L(n − N) + L(X_smooth − X_flat). So a
// copy whose M1-placed atoms fill the box c ± h (about its origin) lies in c ± (h + E·(|c| + h) +
// that offset's bound, per axis in copy_boxes), with E the element-wise largest |T − I|, σ L's
// largest singular value, δ = max |n_i − N| over corners (n(uv_m) of an owned copy is a positive
// combination of them) and b the smooth surface's largest lift off its facet (chart_smooth_bulge). E
// is sampled over each triangle (a barycentric grid, where owned copies sit) and widened by a fifth
// plus 0.02 for what lies between samples. Along N the lift reaches tens of Å on coarse facets; the
// shader shears each slot's ray onto the tile's lift plane (chart_lift_shear_ray), so a sheared
// triangle's boxes hold only what the plane misses: the curvature term, exact per copy, and the
// plane's slope across the copy's own width.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace nano::placement {

struct MembraneDistortion {
  double sigma = 0, delta = 0, bulge = 0;
  double lift_lo = 0, lift_hi = 0;  // range of the smooth surface's lift along the face normal (tile z)
  glm::dmat3 e{0.0};                // element-wise max |T − I|
  // Sheared triangles: ranges of chart_smooth_lift_curvature (column r: tile component r; lo > hi:
  // none in this bound) and the largest |∂plane/∂x|, |∂plane/∂y| per component. Unsheared ones:
  // their lift range along the normal (lo > hi: none).
  glm::dmat3 curvature_lo{glm::dvec3(INFINITY), glm::dvec3(INFINITY), glm::dvec3(INFINITY)};
  glm::dmat3 curvature_hi{glm::dvec3(-INFINITY), glm::dvec3(-INFINITY), glm::dvec3(-INFINITY)};
  bool has_sheared() const { return curvature_lo[0].x <= curvature_hi[0].x; }
  bool has_unsheared() const { return unsheared_lo <= unsheared_hi; }
  glm::dvec3 slope_x{0.0}, slope_y{0.0};
  double unsheared_lo = INFINITY, unsheared_hi = -INFINITY;
  double plane_error = 0;  // the float plane's rounding (Å), shader and host alike
};

// Widens `into` (nothing yet: the first distortion) to hold o.
void widen_to(std::optional<MembraneDistortion>& into, const MembraneDistortion& o);

// Range of the lift left over by the plane for a copy at Δ from the tile's centre (tile Å) under
// curvatures in [lo, hi]: Δx²·h.x + 2·Δx·Δy·h.y + Δy²·h.z, each term linear in its h.
std::pair<double, double> curvature_range(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec2& delta);

// One mesh triangle as the package stores it: corner positions, normals and UVs (compartment space).
struct MembraneTriangleCorners {
  std::array<glm::vec3, 3> position, normal;
  std::array<glm::vec2, 3> uv;
};
// A compartment's membrane tiling, as the renderer's records hold it.
struct MembraneTiling {
  float tile_uv;     // s: a Wang square's size in UV (RenderCompartment.membrane.x)
  float s_over_S;    // s over its size in Å (membrane.y)
  float half;        // the tile point its lift planes are taken at (membrane.z)
  float smoothness;  // the smooth surface's shape factor (Compartment.scales.w)
};

// One triangle's distortion (already widened for what lies between samples), or nothing for a
// triangle that owns no copy.
std::optional<MembraneDistortion> triangle_distortion(const MembraneTriangleCorners& corners, const MembraneTiling& tiling);

// Where a copy at tile-space position `pos` whose M1-placed atoms fill c ± h about it (bounding
// radius r) can lie, under distortion d: `lo`/`hi` in its slot's sheared tile space (its mLAS box),
// `reach_lo`/`reach_hi` in the unsheared one (the repLAS and slot boxes, which the origin tile's
// ray meets). `half` is the tile point the lift planes are taken at (RenderCompartment.membrane.z).
struct CopyBoxes {
  glm::dvec3 lo, hi, reach_lo, reach_hi;
};
CopyBoxes copy_boxes(const glm::dvec3& pos, const glm::dvec3& c, const glm::dvec3& h, double r, const MembraneDistortion& d,
                     double half);

// Distortion classes: an mLAS box must hold its copy wherever a triangle places it, but triangles
// differ (on the red blood cell the smooth surface lifts copies 17–80 Å off their facets, and one
// bound for all made a ray meet ~40 molecule boxes to hit one). The compartment's triangles are
// ranked by how far they widen a typical lipid's box and split at kClassShare; class k gets its own
// copy of every square's mLAS, widened for its own worst triangle, and a triangle's slots query its
// class's. Two classes, the best three quarters and the rest: red blood cell frames 1.34× faster at
// its scene camera for 7 MB more device memory (four classes: 10 MB more, 1.34×).
inline constexpr std::uint32_t kDistortionClasses = 2;
inline constexpr double kClassShare[kDistortionClasses] = {0.75, 1.0};
struct DistortionClasses {
  std::vector<std::uint8_t> of_triangle;  // per triangle of the mesh
  std::vector<bool> unsheared;            // per triangle: its slots' rays are not sheared
  std::array<std::optional<MembraneDistortion>, kDistortionClasses> bound;
};
// The classes of a mesh's triangles from their distortions (triangle_distortion, in mesh order).
DistortionClasses distortion_classes(std::span<const std::optional<MembraneDistortion>> per_triangle, double half);

}  // namespace nano::placement
