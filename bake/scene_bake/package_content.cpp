#include "bake/scene_bake/package_content.hpp"

#include "format/core_skip.hpp"

#include <algorithm>
#include <functional>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

#include "bake/structure/coarse_beads.hpp"

namespace nano::scene_bake {
namespace {

template <class Vector>
std::uint32_t checked_index(const Vector& v) {
  if (v.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("package section exceeds 2^32 records");
  return static_cast<std::uint32_t>(v.size());
}

template <std::size_t N>
void copy_text(char (&field)[N], const std::string& text) {
  std::memset(field, 0, N);
  std::memcpy(field, text.data(), std::min(N, text.size()));
}

gpu::MoleculeInstance make_instance(const tiles::Instance& instance, std::uint32_t molecule,
                                    const BakedMolecule& type) {
  gpu::MoleculeInstance record{};
  const glm::quat& q = instance.rotation;
  record.rotation = glm::vec4(q.x, q.y, q.z, q.w);
  record.position = glm::vec4(instance.position, 0.f);
  const glm::mat3 rotation = glm::mat3_cast(q);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const structure::Atom& atom : type.atoms) {
    const glm::vec3 p = rotation * glm::vec3(atom.position) + instance.position;
    const float r = static_cast<float>(atom.radius);
    lo = glm::min(lo, p - r);
    hi = glm::max(hi, p + r);
  }
  record.aabb_min = glm::vec4(lo, 0.f);
  record.aabb_max = glm::vec4(hi, 0.f);
  record.molecule_type = molecule;
  record.flags = instance.alternate ? gpu::NANO_INSTANCE_ALTERNATE : 0u;
  return record;
}

}  // namespace

std::pair<std::uint32_t, std::uint32_t> PackageContent::add_string(const std::string& text) {
  const auto offset = checked_index(strings);
  strings += text;
  return {offset, static_cast<std::uint32_t>(text.size())};
}

std::uint32_t PackageContent::add_molecule(const BakedMolecule& molecule) {
  const std::uint32_t index = checked_index(molecules);
  gpu::MoleculeType record{};
  const auto& spheres = molecule.properties.spheres;
  record.aabb_min = glm::vec4(glm::vec3(spheres.min), static_cast<float>(molecule.properties.bounding_radius));
  record.aabb_max = glm::vec4(glm::vec3(spheres.max), 0.f);
  record.up_axis = glm::vec4(glm::vec3(molecule.up), 0.f);
  record.colour = glm::vec4(glm::vec3(molecule.linear_colour), 1.f);
  record.first_atom = checked_index(atoms);
  record.atom_count = static_cast<std::uint32_t>(molecule.atoms.size());
  std::tie(record.name_offset, record.name_length) = add_string(molecule.name);
  std::tie(record.source_offset, record.source_length) = add_string(molecule.source);
  for (const structure::Atom& atom : molecule.atoms) {
    atoms.push_back({glm::vec4(glm::vec3(atom.position), static_cast<float>(atom.radius))});
    format::AtomInfo info{};
    copy_text(info.chain, atom.chain);
    copy_text(info.residue_name, atom.residue_name);
    copy_text(info.atom_name, atom.atom_name);
    copy_text(info.element, atom.element);
    info.insertion_code = atom.insertion_code.empty() ? '\0' : atom.insertion_code[0];
    info.alt_location = atom.alt_loc == ' ' ? '\0' : atom.alt_loc;
    info.residue_number = atom.residue_number;
    atom_info.push_back(info);
  }
  const gpu::BeadRange range{checked_index(beads), 0};
  for (const structure::CoarseBead& bead : structure::coarse_beads(molecule.atoms)) {
    gpu::Bead b{};
    // The float centre moves by up to an ulp: 1e-3 Å keeps every atom sphere inside.
    b.centre_radius = glm::vec4(glm::vec3(bead.centre), static_cast<float>(bead.radius + 1e-3));
    b.atom = record.first_atom + bead.representative;
    b.atom_count = bead.atom_count;
    beads.push_back(b);
  }
  bead_ranges.push_back({range.first, checked_index(beads) - range.first});
  molecules.push_back(record);
  return index;
}

TileRange PackageContent::add_wang_set(const BakedWangSet& baked, const std::vector<BakedMolecule>& library) {
  const tiles::WangSet& set = baked.set;
  TileRange range{set.dims == 2 ? checked_index(tiles2d) : checked_index(tiles3d),
                  static_cast<std::uint32_t>(set.tiles.size())};
  for (const tiles::WangTile& tile : set.tiles) {
    const std::uint32_t first_instance = checked_index(instances);
    for (const tiles::Instance& instance : tile.instances) {
      const std::uint32_t molecule = baked.molecule_of_type[instance.type];
      instances.push_back(make_instance(instance, molecule, library[molecule]));
    }
    const auto& c = tile.colours;  // [axis][low, high]
    const auto count = static_cast<std::uint32_t>(tile.instances.size());
    if (set.dims == 2) {
      gpu::Tile2D record{};
      record.edge_colours = glm::uvec4(c[1][1], c[0][1], c[1][0], c[0][0]);  // N, E, S, W
      record.size = glm::vec4(set.edge, set.edge, tile.atoms_max.z - tile.atoms_min.z, 0.f);
      record.first_instance = first_instance;
      record.instance_count = count;
      tiles2d.push_back(record);
    } else {
      gpu::Tile3D record{};
      record.face_colours_xy = glm::uvec4(c[0][0], c[0][1], c[1][0], c[1][1]);
      record.face_colours_z = glm::uvec4(c[2][0], c[2][1], 0u, 0u);
      record.size = glm::vec4(set.edge, set.edge, set.edge, 0.f);
      record.first_instance = first_instance;
      record.instance_count = count;
      tiles3d.push_back(record);
    }
  }
  return range;
}

std::uint32_t PackageContent::add_recipe(const tiles::TilingRecipe& recipe, const TileRange& set) {
  gpu::Recipe record{};
  record.dims = glm::uvec4(recipe.size[0], recipe.size[1], recipe.size[2],
                           recipe.dims == 2 ? gpu::NANO_RECIPE_2D : gpu::NANO_RECIPE_3D);
  record.first_index = checked_index(recipe_indices);
  record.index_count = static_cast<std::uint32_t>(recipe.cells.size());
  for (const std::uint32_t cell : recipe.cells) recipe_indices.push_back(set.first + cell);
  const std::uint32_t index = checked_index(recipes);
  recipes.push_back(record);
  return index;
}

std::uint32_t PackageContent::add_mesh(const PackedMesh& mesh, const std::vector<gpu::TriangleShell>& shells,
                                      const std::vector<std::vector<std::uint32_t>>& dropped) {
  // Invariants, not input: the baker builds the shells and drop lists from this very mesh.
  if (shells.size() != mesh.triangles.size()) throw std::invalid_argument("add_mesh: one shell per triangle");
  if (!dropped.empty() && dropped.size() != mesh.triangles.size())
    throw std::invalid_argument("add_mesh: one drop list per triangle");
  for (const std::vector<std::uint32_t>& keys : dropped)
    if (std::adjacent_find(keys.begin(), keys.end(), std::greater_equal<>()) != keys.end())
      throw std::invalid_argument("add_mesh: dropped-copy keys must ascend strictly");
  gpu::Mesh record{};
  record.aabb_min = glm::vec4(mesh.aabb_min, 0.f);
  record.aabb_max = glm::vec4(mesh.aabb_max, 0.f);
  record.first_vertex = checked_index(vertex_positions);
  record.vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
  record.first_triangle = checked_index(triangles);
  record.triangle_count = static_cast<std::uint32_t>(mesh.triangles.size());
  vertex_positions.insert(vertex_positions.end(), mesh.positions.begin(), mesh.positions.end());
  vertex_normals.insert(vertex_normals.end(), mesh.normals.begin(), mesh.normals.end());
  vertex_uvs.insert(vertex_uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
  triangles.insert(triangles.end(), mesh.triangles.begin(), mesh.triangles.end());
  triangle_shells.insert(triangle_shells.end(), shells.begin(), shells.end());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t first = checked_index(dropped_copies);
    if (!dropped.empty()) dropped_copies.insert(dropped_copies.end(), dropped[t].begin(), dropped[t].end());
    triangle_drops.push_back({first, static_cast<std::uint32_t>(dropped_copies.size() - first)});
  }
  const std::uint32_t index = checked_index(meshes);
  meshes.push_back(record);
  return index;
}

std::uint32_t PackageContent::add_occupancy(const std::vector<std::uint8_t>& classes) {
  const std::uint32_t offset = checked_index(occupancy);
  occupancy.insert(occupancy.end(), classes.begin(), classes.end());
  return offset;
}

std::pair<std::uint32_t, std::uint32_t> PackageContent::add_keep_masks(const grid::KeepMasks& masks,
                                                                     std::uint32_t largest_cube) {
  const std::uint32_t words_per_box = (largest_cube + 31) / 32;
  const std::uint32_t first = checked_index(boundary_boxes);
  for (std::size_t b = 0; b < masks.boundary_boxes.size(); ++b) {
    boundary_boxes.push_back({masks.boundary_boxes[b], checked_index(mask_words)});
    const auto mask = masks.mask_of(masks.boundary_boxes[b]);
    for (std::uint32_t w = 0; w < words_per_box; ++w) mask_words.push_back(w < mask.size() ? mask[w] : 0u);
  }
  return {first, static_cast<std::uint32_t>(masks.boundary_boxes.size())};
}

void PackageContent::add_core_skip() {
  core_skip = format::core_skip_section({compartments, occupancy, tiles3d, recipes, recipe_indices, boundary_boxes, mask_words});
}

void PackageContent::add_medium(const BakedMedium& m, const TileRange& cubes, std::uint32_t largest_cube) {
  gpu::Medium record{};
  record.region_min = glm::vec4(glm::vec3(m.region.min), static_cast<float>(m.box_edge));
  record.region_max = glm::vec4(glm::vec3(m.region.max), static_cast<float>(m.clearance));
  record.boxes = glm::uvec4(m.boxes, add_recipe(m.recipe, cubes));
  record.tiles = glm::uvec4(cubes.first, cubes.count, largest_cube, 0u);
  medium.push_back(record);
  for (const grid::ExclusionField& f : m.fields) {
    gpu::ExclusionField field{};
    field.origin = glm::vec4(glm::vec3(f.origin), static_cast<float>(f.spacing));
    field.dims = glm::uvec4(glm::uvec3(f.dims), checked_index(exclusion_values));
    field.limits = glm::vec4(static_cast<float>(f.margin), static_cast<float>(f.clamp), 1.0f / field.origin.w, 0.0f);
    exclusion_fields.push_back(field);
    exclusion_values.insert(exclusion_values.end(), f.values.begin(), f.values.end());
  }
}

std::vector<format::SectionSource> PackageContent::sections() const {
  using format::SectionKind;
  using format::section_source;
  std::vector<format::SectionSource> s;
  const auto add = [&s](SectionKind kind, auto span) {
    if (!span.empty()) s.push_back(section_source(kind, span));
  };
  add(SectionKind::strings, std::span<const char>(strings.data(), strings.size()));
  add(SectionKind::molecules, std::span(molecules));
  add(SectionKind::atoms, std::span(atoms));
  add(SectionKind::atom_info, std::span(atom_info));
  add(SectionKind::beads, std::span(beads));
  add(SectionKind::bead_ranges, std::span(bead_ranges));
  add(SectionKind::tiles2d, std::span(tiles2d));
  add(SectionKind::tiles3d, std::span(tiles3d));
  add(SectionKind::instances, std::span(instances));
  add(SectionKind::recipes, std::span(recipes));
  add(SectionKind::recipe_indices, std::span(recipe_indices));
  add(SectionKind::meshes, std::span(meshes));
  const auto add_mesh_data = [&](SectionKind kind, auto span) {
    if (!span.empty()) s.push_back(section_source(kind, span, mesh_compression));
  };
  add_mesh_data(SectionKind::vertex_positions, std::span(vertex_positions));
  add_mesh_data(SectionKind::vertex_normals, std::span(vertex_normals));
  add_mesh_data(SectionKind::vertex_uvs, std::span(vertex_uvs));
  add_mesh_data(SectionKind::triangles, std::span(triangles));
  add(SectionKind::triangle_shells, std::span(triangle_shells));
  // Required (their rows in format/section_table.hpp): a 2.1 reader that skipped them would render the
  // copies that clash.
  if (!dropped_copies.empty()) {
    s.push_back(section_source(SectionKind::triangle_drops, std::span(triangle_drops)));
    s.push_back(section_source(SectionKind::dropped_copies, std::span(dropped_copies)));
  }
  add(SectionKind::compartments, std::span(compartments));
  add(SectionKind::occupancy, std::span(occupancy));
  add(SectionKind::boundary_boxes, std::span(boundary_boxes));
  add(SectionKind::mask_words, std::span(mask_words));
  add(SectionKind::core_skip, std::span(core_skip));
  add(SectionKind::medium, std::span(medium));
  add(SectionKind::exclusion_fields, std::span(exclusion_fields));
  add(SectionKind::exclusion_values, std::span(exclusion_values));
  add(SectionKind::scene, std::span(&scene, 1));
  add(SectionKind::effects, std::span(effects));
  add(SectionKind::keyframes, std::span(keyframes));
  add(SectionKind::compartment_instances, std::span(compartment_instances));
  add(SectionKind::provenance, std::span<const char>(provenance.data(), provenance.size()));
  return s;
}

}  // namespace nano::scene_bake
