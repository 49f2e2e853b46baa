#pragma once
// Typed views of every section of an open package, named like the sections, so the readers that
// walk a whole scene (the explicit-instancing oracle, the renderer's upload) declare them once.
// Spans point into the Package, which must outlive the view; an absent section is an empty span.
#include <cstdint>
#include <algorithm>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "format/package.hpp"

namespace nano::format {

// A compartment instance's 3×4 row-major transform (compartment space → world) in double:
// world = linear·p + translation.
struct InstanceTransform {
  glm::dmat3 linear{1.0};
  glm::dvec3 translation{0.0};
};
inline InstanceTransform instance_transform(const gpu::CompartmentInstance& ci) {
  InstanceTransform t;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.linear[c][r] = ci.transform[r][c];  // GLM is column-major
    t.translation[r] = ci.transform[r][3];
  }
  return t;
}

struct PackageView {
  // One span per section, named and typed by format/section_table.hpp: e.g. tiles2d, triangle_drops
  // (empty: no drops, else parallel to triangles), beads (format 2.5; empty: no level of detail).
#define NANO_SECTION_SPAN(name, value, record, ...) std::span<const record> name;
  NANO_SECTION_TABLE(NANO_SECTION_SPAN)
#undef NANO_SECTION_SPAN

  explicit PackageView(const Package& p) {
#define NANO_SECTION_INIT(name, ...) name = p.records<SectionKind::name>();
    NANO_SECTION_TABLE(NANO_SECTION_INIT)
#undef NANO_SECTION_INIT
  }

  // The tile of recipe `recipe` at cell (a, b, c): recipes wrap in every direction, both ways.
  // Entries are absolute tile indices: the validator requires them inside the compartment's tile
  // set [first, first + count), so adding membrane_first_tile / soluble_first_tile again (as
  // docs/placement.md's formulas read) would leave the set whenever first > 0.
  std::uint32_t recipe_cell(std::uint32_t recipe, std::int64_t a, std::int64_t b, std::int64_t c) const {
    const auto wrap = [](std::int64_t x, std::uint32_t n) {
      const std::int64_t r = x % static_cast<std::int64_t>(n);
      return static_cast<std::uint32_t>(r < 0 ? r + n : r);
    };
    const gpu::Recipe& r = recipes[recipe];
    return recipe_indices[r.first_index + wrap(a, r.dims.x) + r.dims.x * (wrap(b, r.dims.y) + r.dims.y * wrap(c, r.dims.z))];
  }

  // True iff the baker listed membrane copy `key` (membrane_copy_key) of triangle t (dropped, or an
  // alternate shown: membrane_copy_listed_shows): a binary search over the triangle's ascending keys,
  // as the shader does.
  bool membrane_copy_listed(std::uint32_t t, std::uint32_t key) const {
    if (triangle_drops.empty()) return false;
    const auto keys = dropped_copies.subspan(triangle_drops[t].first, triangle_drops[t].count);
    return std::binary_search(keys.begin(), keys.end(), key);
  }

  // Per molecule type, the radius about its origin that holds every atom sphere (max |centre| +
  // radius), computed from the atoms themselves rather than trusted from MoleculeType.aabb_min.w.
  std::vector<double> atom_bounding_radii() const {
    std::vector<double> radii;
    for (const gpu::MoleculeType& m : molecules) {
      double r = 0;
      for (std::uint32_t a = m.first_atom; a < m.first_atom + m.atom_count; ++a)
        r = std::max(r, glm::length(glm::dvec3(glm::vec3(atoms[a].centre_radius))) + atoms[a].centre_radius.w);
      radii.push_back(r);
    }
    return radii;
  }
};

}  // namespace nano::format
