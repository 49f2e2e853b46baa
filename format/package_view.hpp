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
  std::span<const gpu::MoleculeType> molecules;
  std::span<const gpu::Atom> atoms;
  std::span<const AtomInfo> atom_info;
  std::span<const gpu::Tile2D> squares;
  std::span<const gpu::Tile3D> cubes;
  std::span<const gpu::MoleculeInstance> instances;
  std::span<const gpu::Recipe> recipes;
  std::span<const std::uint32_t> recipe_indices;
  std::span<const gpu::Mesh> meshes;
  std::span<const glm::vec4> positions, normals;
  std::span<const glm::vec2> uvs;
  std::span<const gpu::Triangle> triangles;
  std::span<const gpu::TriangleShell> shells;
  std::span<const gpu::Compartment> compartments;
  std::span<const std::uint8_t> occupancy;
  std::span<const gpu::CompartmentInstance> compartment_instances;
  std::span<const gpu::BoundaryBox> boundary_boxes;
  std::span<const std::uint32_t> mask_words;
  std::span<const gpu::TriangleDrops> triangle_drops;  // empty (no drops) or parallel to triangles
  std::span<const std::uint32_t> dropped_copies;
  std::span<const gpu::Bead> beads;                // format 2.5; empty: no level of detail
  std::span<const gpu::BeadRange> bead_ranges;     // empty or parallel to molecules

  explicit PackageView(const Package& p)
      : molecules(p.records<SectionKind::molecules>()),
        atoms(p.records<SectionKind::atoms>()),
        atom_info(p.records<SectionKind::atom_info>()),
        squares(p.records<SectionKind::tiles2d>()),
        cubes(p.records<SectionKind::tiles3d>()),
        instances(p.records<SectionKind::instances>()),
        recipes(p.records<SectionKind::recipes>()),
        recipe_indices(p.records<SectionKind::recipe_indices>()),
        meshes(p.records<SectionKind::meshes>()),
        positions(p.records<SectionKind::vertex_positions>()),
        normals(p.records<SectionKind::vertex_normals>()),
        uvs(p.records<SectionKind::vertex_uvs>()),
        triangles(p.records<SectionKind::triangles>()),
        shells(p.records<SectionKind::triangle_shells>()),
        compartments(p.records<SectionKind::compartments>()),
        occupancy(p.records<SectionKind::occupancy>()),
        compartment_instances(p.records<SectionKind::compartment_instances>()),
        boundary_boxes(p.records<SectionKind::boundary_boxes>()),
        mask_words(p.records<SectionKind::mask_words>()),
        triangle_drops(p.records<SectionKind::triangle_drops>()),
        dropped_copies(p.records<SectionKind::dropped_copies>()),
        beads(p.records<SectionKind::beads>()),
        bead_ranges(p.records<SectionKind::bead_ranges>()) {}

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
