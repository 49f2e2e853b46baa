#pragma once
// Adaptive shell offsets (paper §"Adaptive Shell Space Construction"): per triangle +h, −h and side,
// from the molecules the triangle OWNS, such that each owned molecule's bounding sphere (about its
// molecule-space origin) lies entirely inside the triangle's prism (shell_prism.h). The offsets are
// estimated from the molecules, then VERIFIED against the actual float prism and grown until every
// sphere passes a conservative containment test (see compute_shell_offsets).
#include <cstddef>
#include <vector>

#include "bake/shell/membrane_mapping.hpp"
#include "bake/tiles/molecule_type.hpp"
#include "shared/shell_prism.h"

namespace nano::shell {

// Radius about the molecule-space origin that contains every atom sphere: max |centre| + radius
// (the origin is the point the tile places, not the atoms' centroid). 0 for a molecule without atoms.
float molecule_origin_radius(const tiles::MoleculeType& type);

// Safety margin (Å) every sphere keeps from the prism boundary: covers the float rounding of the
// molecule transforms and atom positions the renderer computes (~1e-3 Å at 4·10⁴ Å).
inline constexpr double kShellContainmentMargin = 0.01;

struct ShellStats {
  std::size_t owned_molecules = 0;           // summed over triangles, alternates included
  std::size_t triangles_with_molecules = 0;
  std::size_t grown_triangles = 0;           // the estimate failed verification and was grown
  int max_grow_iterations = 0;
  std::size_t uncontained_triangles = 0;     // still failing after the iteration bound without droppable copies
  std::size_t unfit_triangles = 0;           // contained only once droppable copies were dropped
  std::size_t inverted_caps = 0;             // triangles whose cap faces against the face normal
  double min_vertex_normal_cos = 1.0;        // smallest cos(n_i, face normal) among used triangles
};

struct ShellResult {
  std::vector<gpu::ShellOffsets> offsets;  // per triangle; zero for triangles owning nothing
  // Per triangle: how far the copies it keeps reach from it, the most over them of the distance
  // from the centre to the triangle plus the radius, rounded up by kShellContainmentMargin (Å; 0
  // for none). Every atom the triangle draws lies within it of the triangle: what the medium's
  // exclusion field keeps clear, triangle by triangle (a spike's reach stays on its own triangles).
  std::vector<float> reach;
  gpu::ShellOffsets fixed{0.f, 0.f, 0.f};  // fixed_offsets(offsets)
  ShellStats stats;
  // Per molecule type (index into `types`): owned molecules summed over triangles, alternates not
  // counted (they show only where the pruning lists them), so a caller counting copies need not
  // enumerate the membrane a second time.
  std::vector<std::size_t> owned_by_type;
  // Copies of droppable types left out because their triangle's prism could not contain them (a
  // spike in a narrow fold): per triangle, ascending membrane copy keys (MembraneMapping::copy_key),
  // and their count per type. They count in owned_by_type; the caller drops them.
  std::vector<std::vector<std::uint32_t>> dropped;
  std::vector<std::size_t> dropped_by_type;
  // Triangles that no prism fits even without droppable copies (uncontained_triangles of them).
  std::vector<std::uint32_t> uncontained;
  // All of them again: each gets the prism that fits once copies of any type are left out (lipids
  // too, largest first; at worst all of them, a flat prism), in `dropped` and `dropped_by_type`. A
  // caller decides whether so few holes in the bilayer are acceptable.
  std::vector<std::uint32_t> lipids_left_out;
};

// Fixed-height alternative: componentwise maximum over triangles (the runtime can derive it from
// the stored per-triangle values). "No overlap" variants set side to 0.
gpu::ShellOffsets fixed_offsets(const std::vector<gpu::ShellOffsets>& offsets);

// The prism of triangle t of `mapping` with `offsets` (shell_prism_make on the mapping's float
// corners and unit normals).
gpu::Prism triangle_prism(const MembraneMapping& mapping, std::size_t t, const gpu::ShellOffsets& offsets);

// Offsets for every triangle of `mapping`; `types` are the molecule types the Wang set's instances
// index. Estimate per triangle (face normal N, c_min = min_i n_i·N clamped to ≥ 0.1): over the owned
// molecules (centre c, radius r, barycentrics λ of uv_m), h+ = max((c−P0)·N + r)/c_min,
// h− = max(r − (c−P0)·N)/c_min, side = max_k (r − λ_k·altitude_k)/c_min, all ≥ 0. Verification on the
// float prism, conservatively: the sphere must keep distance r + margin from both cap PLANES and
// from each wall's supporting half-space {x·w ≤ min over the wall's 4 corners of corner·w}, w the
// outward normal of the bilinear wall at its centre (a bilinear function reaches its extremes at the
// corners, so the wall lies outside that half-space); the intersection K of those five half-spaces
// meets no face, so it lies wholly inside or outside the prism, decided once per triangle by
// prism_intersect parity from one molecule's centre (3 directions agree). A failing triangle grows
// the offending offset(s) by the deficit / c_min and retries (at most 64 times).
// A triangle whose molecules no prism contains leaves out copies of `droppable` types (indexed like
// `types`; empty: none), largest first, until one does: a protein too tall for a fold is dropped
// there rather than the bake; the lipids decide the shell.
// Throws InputError("shell", ...) when an instance's type is not in `types` (with several threads:
// the error of the lowest such triangle, as with one).
// threads ≥ 1 splits the triangles into contiguous blocks run by parallel_for; every triangle is
// computed alone and the statistics are order-free sums, minima and maxima, so the result does not
// depend on `threads`.
ShellResult compute_shell_offsets(const MembraneMapping& mapping, const std::vector<tiles::MoleculeType>& types,
                                  int threads = 1, const std::vector<bool>& droppable = {});

}  // namespace nano::shell
