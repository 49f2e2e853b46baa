#pragma once
// Section "core_skip" (format 2.7): per cell of every core grid widened by one box, the skip level of
// shaders/shared/core_skip.h. One derivation, used by the baker to write the section, by the
// validator to check it cell for cell, and by the runtime for packages that lack it (before 2.7).
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "shaders/shared/package_records.h"

namespace nano::format {

// The sections a core grid's boxes are read from (already checked by the validator's rules of
// compartments, recipes, tiles3d and the keep-masks).
struct CoreGridRecords {
  std::span<const gpu::Compartment> compartments;
  std::span<const std::uint8_t> occupancy;
  std::span<const gpu::Tile3D> tiles3d;
  std::span<const gpu::Recipe> recipes;
  std::span<const std::uint32_t> recipe_indices;
  std::span<const gpu::BoundaryBox> boundary_boxes;
  std::span<const std::uint32_t> mask_words;
};

// Cells per axis of compartment c's widened grid: its boxes plus one on each side.
glm::uvec3 core_skip_cells(const gpu::Compartment& c);
std::uint64_t core_skip_cell_count(const gpu::Compartment& c);

// Per box of compartment `ci`'s core grid (x fastest): 1 if it holds a copy a ray can hit.
std::vector<std::uint8_t> core_live_boxes(const CoreGridRecords& records, std::uint32_t ci);

// Per cell of the widened grid of a core grid of `boxes` boxes (x fastest): the skip level, from its
// live boxes (one byte per box).
std::vector<std::uint8_t> core_skip_levels(glm::uvec3 boxes, std::span<const std::uint8_t> live);

// Per compartment: the first cell of its levels in the section (kNoCoreGrid without a core grid),
// and the section's cell count.
inline constexpr std::uint64_t kNoCoreGrid = ~std::uint64_t{0};
struct CoreSkipLayout {
  std::vector<std::uint64_t> first_cell;
  std::uint64_t cells = 0;
};
CoreSkipLayout core_skip_layout(std::span<const gpu::Compartment> compartments);

// The section's bytes: every compartment with a core grid in order, its levels two a byte.
std::vector<std::uint8_t> core_skip_section(const CoreGridRecords& records);

}  // namespace nano::format
