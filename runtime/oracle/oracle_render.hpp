#pragma once
// The CPU reference image of `nanoview verify`: every pixel's ray (camera_ray_direction of
// shaders/shared/camera.h, on the same floats as the GPU) intersected exactly, in double, with the
// atom spheres of the molecule copies ExplicitScene places explicitly. What the GPU renders by
// virtual instancing must match it pixel by pixel.
//
// Hit rule (the GPU must follow the same one): a pixel shows the atom sphere with the smallest
// root t ≥ 0 of |eye + t·d − centre| = radius, d the pixel's direction renormalised in double, so
// depth is Å along the unit ray. An eye inside an atom therefore sees that atom's far side. Exact
// ties go to the smaller (copy number, atom).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "format/package.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "shared/camera.h"

namespace nano::oracle {

struct OracleRenderOptions {
  // Atoms held at once (≈ 70 bytes each with the BVH). A round that would need more hands its
  // pixels to ray tubes (below), or throws InputError when they are off.
  std::uint64_t max_atoms = 30'000'000;
  // Pixels a round cannot hold are traced alone: each ray through its own tube, Å by Å (a whole cell
  // seen from afar, a cut-away). At most this many tube segments in all, then InputError.
  bool ray_tubes = true;
  // Every pixel through its ray's tube from the start, no rounds: for views whose rounds cost more
  // than they save — a whole scene from afar, a cut-away of a cell (a round's box is the AABB of a
  // wide pyramid, and a rotated cell's copies are enumerated over its compartment-space bounds).
  bool tubes_only = false;
  std::uint64_t max_tube_segments = 3'000'000;
  unsigned threads = 2;
  // First depth bound: the nearest compartment instance's reach plus this many Å.
  double first_margin = 300.0;
  std::string camera_name = "camera";  // for error messages
  // Every atom radius times this: verify renders the view again with radii 1 ± ε to tell which
  // differences a change of ε·r could flip (grazing touches, float ties) from real ones.
  double radius_scale = 1.0;
  // Clipping half-spaces (unit n, d) in world Å: an atom whose centre p has n·p + d < 0 for one of
  // them is left out whole (runtime/render/effects.hpp clip_half_spaces).
  std::vector<glm::dvec4> clip;
  // Trace only these pixels (row-major indices; the others stay background), e.g. the few a verify
  // view disagrees on; empty: every pixel. A traced pixel gets the hit the whole image would give it.
  std::vector<std::uint32_t> only_pixels;
};

// What one render cost; for reports and for choosing cameras.
struct OracleRenderStats {
  int rounds = 0;
  std::uint64_t tube_rays = 0;      // pixels traced alone, through their ray's tube
  std::uint64_t tube_segments = 0;  // the tube segments those took
  std::uint64_t atoms_last_round = 0;  // atoms held by the last (largest) round
  std::uint64_t atoms_total = 0;       // summed over rounds
  double final_depth_bound = 0;        // D of the last round, Å
  double seconds = 0;
};

// Row-major image of camera.size.x × camera.size.y pixels, row 0 at the top (camera.h).
std::vector<gpu::PixelHit> oracle_render(const ExplicitScene& scene, const format::Package& package,
                                         const gpu::Camera& camera, const OracleRenderOptions& options = {},
                                         OracleRenderStats* stats = nullptr);

// The background pixel: depth +inf, every id kNoHit (cell: all bits set).
gpu::PixelHit background_pixel();

// Smallest root t ≥ 0 of the ray (unit direction) against the sphere, or +inf: the entry, or where
// the ray leaves the sphere when it starts inside. The discriminant from the perpendicular distance
// and the roots from q = −(β + sign β·√Δ), so grazing and distant rays keep their digits (Ray
// Tracing Gems ch. 7), even though this runs in double.
double first_sphere_hit(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& centre, double radius);

// A conservative world AABB of everything the package can place (atoms included); used to know
// when a ray has left the scene. Built from vertices, grid dims and atoms, not from stored AABBs.
// With `scene`, its instances stand where it put them (animation); else where the package does.
WorldBox scene_world_bounds(const format::Package& package, const ExplicitScene* scene = nullptr);

}  // namespace nano::oracle
