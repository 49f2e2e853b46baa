#pragma once
// Which soluble molecules of each BOUNDARY box's Wang cube are kept, and how many copies the
// whole core grid represents.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/grid/box_occupancy.hpp"
#include "bake/grid/mesh_surface.hpp"

namespace nano::grid {

struct CubeMolecule {
  glm::dvec3 centre{0.0};  // cube space, in [0, S)³: the cube owns the molecules centred in it
  double radius = 0.0;     // bounding radius, Å
  std::uint32_t type = 0;  // molecule type, for the per-type copy counts
};
using CubeContents = std::vector<CubeMolecule>;            // one Wang cube; bit m of a mask = molecule m
using CubeRecipe = std::function<std::uint32_t(const glm::ivec3&)>;  // box (i, j, k) → cube index

// Sparse masks, only for BOUNDARY boxes. Memory: 8 bytes per BOUNDARY box (its linear index
// and its first word) + ceil(molecules of its cube / 32) words of 4 bytes; nothing per other box.
// Lookup is a binary search in boundary_boxes.
struct KeepMasks {
  std::vector<BoxIndex> boundary_boxes;     // ascending linear indices of the BOUNDARY boxes
  std::vector<std::uint32_t> word_offsets;  // size boundary_boxes.size() + 1
  std::vector<std::uint32_t> words;         // molecule m is kept iff bit (m % 32) of word m / 32 is set
  std::uint64_t kept = 0, dropped = 0;      // molecules of BOUNDARY boxes

  std::size_t bytes() const;
  // The mask of a BOUNDARY box; empty for any other box.
  std::span<const std::uint32_t> mask_of(BoxIndex box) const;
};

// A molecule of a BOUNDARY box is kept iff its centre is strictly inside the mesh and its
// distance to the surface is ≥ radius + shell_clearance (it stays clear of the membrane shell and
// is never cut by the surface). Molecules of INSIDE boxes are kept implicitly, which is only sound
// if shell_clearance + every radius ≤ occupancy.clearance: checked. The decision is exact per
// molecule (local brute-force distances to the triangles CGAL finds near the box), with one CGAL
// inside query per box and only the molecules far from the box centre queried themselves.
// Throws nano::InputError for a molecule centre outside [0, S)³, a negative or non-finite radius,
// a recipe index out of range, a clearance that breaks the rule above, or > 2^32 mask words.
KeepMasks compute_keep_masks(const MeshSurface& surface, const BoxOccupancy& occupancy,
                             const std::vector<CubeContents>& cubes, const CubeRecipe& recipe,
                             double shell_clearance, int threads = 1);

// Soluble copies the grid represents per molecule type (index = type, size = largest type + 1):
// (INSIDE boxes of each cube) × (that cube's count per type) + the kept bits of BOUNDARY boxes.
std::vector<std::uint64_t> represented_copies(const BoxOccupancy& occupancy, const std::vector<CubeContents>& cubes,
                                              const CubeRecipe& recipe, const KeepMasks& masks);

}  // namespace nano::grid
