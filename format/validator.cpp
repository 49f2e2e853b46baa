#include "format/validator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "common/effect_table.hpp"
#include "format/checked_math.hpp"
#include "format/core_skip.hpp"

namespace nano::format {
namespace {

using glm::uvec4;
using glm::vec2;
using glm::vec4;

std::string str(std::uint64_t v) { return std::to_string(v); }

class SemanticCheck {
public:
  explicit SemanticCheck(const Package& p) : p_(p) {}

  // The rule of each row of format/section_table.hpp, each rule once where its first row stands,
  // after the needs of every row it checks.
  void run() {
    using RuleFunction = void (SemanticCheck::*)();
    static constexpr RuleFunction kRules[] = {
#define NANO_SECTION_RULE(name, value, record, flags, since, codecs, rule, ...) &SemanticCheck::rule,
        NANO_SECTION_TABLE(NANO_SECTION_RULE)
#undef NANO_SECTION_RULE
    };
    static_assert(std::size(kRules) == kSectionTable.size());
    for (std::size_t i = 0; i < std::size(kRules); ++i) {
      if (std::find(kRules, kRules + i, kRules[i]) != kRules + i) continue;  // ran at its first row
      for (std::size_t j = i; j < std::size(kRules); ++j)
        if (kRules[j] == kRules[i])
          for (const SectionKind needed : kSectionTable[j].needs) require(kSectionTable[j].kind, needed);
      (this->*kRules[i])();
    }
  }

private:
  // The record being checked, so failures can name its byte offset.
  struct Cursor {
    SectionKind kind;
    std::uint64_t index;
    std::uint64_t record_size;
  };

  [[noreturn]] void fail(const Cursor& c, std::uint64_t member_offset, Rule rule, const std::string& detail) const {
    const std::string what = section_kind_name(c.kind) + "[" + str(c.index) + "]: " + detail;
    throw PackageError(p_.name(), rule, p_.locate(c.kind, c.index * c.record_size + member_offset), what);
  }

  template <SectionKind K> auto cursor(std::uint64_t i) const { return Cursor{K, i, sizeof(record_t<K>)}; }

  // A section that records of `user` refer to must exist when there is at least one such record.
  void require(SectionKind user, SectionKind needed) const {
    if (p_.record_count(user) > 0 && !p_.has(needed))
      throw PackageError(p_.name(), Rule::missing_section, p_.locate(user, 0),
                         "section " + section_kind_name(user) + " refers to section " + section_kind_name(needed) +
                             ", which is absent");
  }

  void finite(const Cursor& c, std::uint64_t off, const float* v, int n, const char* what) const {
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(v[i])) fail(c, off + 4 * i, Rule::non_finite, std::string(what) + " is not finite");
  }
  void finite(const Cursor& c, std::uint64_t off, const vec4& v, const char* what) const { finite(c, off, &v.x, 4, what); }

  void zero(const Cursor& c, std::uint64_t off, std::uint32_t v) const {
    if (v != 0) fail(c, off, Rule::nonzero_reserved, "reserved member is not zero");
  }

  void ordered_aabb(const Cursor& c, std::uint64_t off_min, const vec4& lo, const vec4& hi) const {
    finite(c, off_min, lo, "AABB minimum");
    finite(c, off_min + 16, hi, "AABB maximum");
    for (int a = 0; a < 3; ++a)
      if (lo[a] > hi[a]) fail(c, off_min + 4 * a, Rule::inverted_aabb, "AABB minimum exceeds maximum on axis " + str(a));
  }

  void range(const Cursor& c, std::uint64_t off, std::uint64_t first, std::uint64_t count, SectionKind target,
             const char* what) const {
    const std::uint64_t size = p_.record_count(target);
    if (!range_within(first, count, size))
      fail(c, off, Rule::index_out_of_range,
           std::string(what) + " [" + str(first) + ", +" + str(count) + ") exceeds the " + str(size) + " records of " +
               section_kind_name(target));
  }

  void index(const Cursor& c, std::uint64_t off, std::uint64_t i, SectionKind target, const char* what) const {
    const std::uint64_t size = p_.record_count(target);
    if (i >= size)
      fail(c, off, Rule::index_out_of_range,
           std::string(what) + " " + str(i) + " is not below the " + str(size) + " records of " + section_kind_name(target));
  }

  void string_ref(const Cursor& c, std::uint64_t off, std::uint32_t first, std::uint32_t length, const char* what) const {
    if (length == 0 && first == 0) return;  // no string
    range(c, off, first, length, SectionKind::strings, what);
  }

  // strings: checked as ranges by the records that refer to them. draco_meshes: decoded and checked
  // by the reader (format/package.cpp).
  void no_rule_of_its_own() {}

  void check_molecules() {
    const auto mols = p_.records<SectionKind::molecules>();
    for (std::uint64_t i = 0; i < mols.size(); ++i) {
      const gpu::MoleculeType& m = mols[i];
      const Cursor c = cursor<SectionKind::molecules>(i);
      ordered_aabb(c, 0, m.aabb_min, m.aabb_max);
      if (m.aabb_min.w < 0) fail(c, 12, Rule::bad_value, "bounding radius is negative");
      finite(c, 32, m.up_axis, "up axis");
      if (glm::dot(glm::vec3(m.up_axis), glm::vec3(m.up_axis)) == 0) fail(c, 32, Rule::bad_value, "up axis is zero");
      finite(c, 48, m.colour, "colour");
      for (int k = 0; k < 4; ++k)
        if (m.colour[k] < 0 || m.colour[k] > 1) fail(c, 48 + 4 * k, Rule::bad_value, "colour component outside [0, 1]");
      if (m.atom_count == 0) fail(c, 68, Rule::bad_value, "molecule type without atoms");
      range(c, 64, m.first_atom, m.atom_count, SectionKind::atoms, "atom range");
      string_ref(c, 72, m.name_offset, m.name_length, "name");
      string_ref(c, 80, m.source_offset, m.source_length, "source id");
      zero(c, 88, m.reserved0);
      zero(c, 92, m.reserved1);
    }
  }

  void check_atoms() {
    const auto atoms = p_.records<SectionKind::atoms>();
    for (std::uint64_t i = 0; i < atoms.size(); ++i) {
      const Cursor c = cursor<SectionKind::atoms>(i);
      finite(c, 0, atoms[i].centre_radius, "atom");
      if (!(atoms[i].centre_radius.w > 0)) fail(c, 12, Rule::bad_value, "atom radius is not positive");
    }
  }

  void check_atom_info() {
    if (!p_.has(SectionKind::atom_info)) return;
    const auto info = p_.records<SectionKind::atom_info>();
    if (info.size() != p_.record_count(SectionKind::atoms))
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::atom_info, 0),
                         "atom_info has " + str(info.size()) + " records for " +
                             str(p_.record_count(SectionKind::atoms)) + " atoms");
    for (std::uint64_t i = 0; i < info.size(); ++i) {
      const Cursor c = cursor<SectionKind::atom_info>(i);
      // Text members: printable ASCII, then only NUL padding.
      const auto* bytes = reinterpret_cast<const unsigned char*>(&info[i]);
      for (std::uint64_t off = 0; off < offsetof(AtomInfo, residue_number); ++off) {
        const unsigned char ch = bytes[off];
        if (ch != 0 && (ch < 0x20 || ch > 0x7e)) fail(c, off, Rule::bad_value, "non-printable character in atom text");
      }
    }
  }

  void check_tiles2d() { check_tiles<SectionKind::tiles2d>(); }
  void check_tiles3d() { check_tiles<SectionKind::tiles3d>(); }
  template <SectionKind K> void check_tiles() {
    const auto tiles = p_.template records<K>();
    for (std::uint64_t i = 0; i < tiles.size(); ++i) {
      const auto& t = tiles[i];
      const Cursor c = cursor<K>(i);
      const std::uint64_t size_at = offsetof(record_t<K>, size);
      finite(c, size_at, t.size, "tile size");
      const int axes = K == SectionKind::tiles2d ? 2 : 3;
      for (int a = 0; a < axes; ++a)
        if (!(t.size[a] > 0)) fail(c, size_at + 4 * a, Rule::bad_value, "tile size is not positive");
      range(c, offsetof(record_t<K>, first_instance), t.first_instance, t.instance_count, SectionKind::instances,
            "instance range");
      zero(c, offsetof(record_t<K>, reserved0), t.reserved0);
      zero(c, offsetof(record_t<K>, reserved1), t.reserved1);
      if constexpr (K == SectionKind::tiles3d) {
        // The core grid shows every instance of a cube: an alternate there would overlap its original.
        const auto inst = p_.records<SectionKind::instances>();
        for (std::uint64_t m = 0; m < t.instance_count; ++m)
          if (inst[t.first_instance + m].flags & gpu::NANO_INSTANCE_ALTERNATE)
            fail(c, offsetof(record_t<K>, first_instance), Rule::bad_value,
                 "instance " + str(m) + " of the cube is an alternate; only membrane squares have alternates");
        zero(c, offsetof(gpu::Tile3D, face_colours_z) + 8, t.face_colours_z.z);
        zero(c, offsetof(gpu::Tile3D, face_colours_z) + 12, t.face_colours_z.w);
      }
    }
  }

  void check_instances() {
    const auto inst = p_.records<SectionKind::instances>();
    for (std::uint64_t i = 0; i < inst.size(); ++i) {
      const gpu::MoleculeInstance& m = inst[i];
      const Cursor c = cursor<SectionKind::instances>(i);
      finite(c, 0, m.rotation, "rotation");
      if (std::abs(glm::dot(m.rotation, m.rotation) - 1.0f) > 1e-3f) fail(c, 0, Rule::bad_value, "rotation is not a unit quaternion");
      finite(c, 16, m.position, "position");
      ordered_aabb(c, 32, m.aabb_min, m.aabb_max);
      index(c, 64, m.molecule_type, SectionKind::molecules, "molecule type");
      if (m.flags != 0 && p_.header().version_minor < 4)
        fail(c, 68, Rule::nonzero_reserved, "flags is reserved before format 2.4");
      if (m.flags & ~gpu::NANO_INSTANCE_ALTERNATE) fail(c, 68, Rule::bad_value, "unknown instance flags");
      zero(c, 72, m.reserved1);
      zero(c, 76, m.reserved2);
    }
  }

  void check_recipes() {
    const auto recipes = p_.records<SectionKind::recipes>();
    const auto indices = p_.records<SectionKind::recipe_indices>();
    for (std::uint64_t i = 0; i < recipes.size(); ++i) {
      const gpu::Recipe& r = recipes[i];
      const Cursor c = cursor<SectionKind::recipes>(i);
      if (r.dims.w != gpu::NANO_RECIPE_2D && r.dims.w != gpu::NANO_RECIPE_3D)
        fail(c, 12, Rule::bad_value, "dimensionality " + str(r.dims.w) + " is neither 2 nor 3");
      if (r.dims.x == 0 || r.dims.y == 0 || r.dims.z == 0) fail(c, 0, Rule::bad_value, "recipe dimension is zero");
      if (r.dims.w == gpu::NANO_RECIPE_2D && r.dims.z != 1) fail(c, 8, Rule::bad_value, "2D recipe with depth other than 1");
      const std::uint64_t cells = std::uint64_t{r.dims.x} * r.dims.y * r.dims.z;  // < 2^96 impossible: checked below
      const auto xy = checked_mul(r.dims.x, r.dims.y);
      const auto xyz = xy ? checked_mul(*xy, r.dims.z) : std::nullopt;
      if (!xyz || *xyz != r.index_count)
        fail(c, 20, Rule::record_size,
             "index count " + str(r.index_count) + " differs from dims product " + (xyz ? str(cells) : std::string("(overflow)")));
      range(c, 16, r.first_index, r.index_count, SectionKind::recipe_indices, "tile index range");
      const SectionKind tiles = r.dims.w == gpu::NANO_RECIPE_2D ? SectionKind::tiles2d : SectionKind::tiles3d;
      const std::uint64_t tile_count = p_.record_count(tiles);
      for (std::uint64_t k = r.first_index; k < std::uint64_t{r.first_index} + r.index_count; ++k)
        if (indices[k] >= tile_count) {
          const Cursor ic = cursor<SectionKind::recipe_indices>(k);
          fail(ic, 0, Rule::index_out_of_range,
               "tile index " + str(indices[k]) + " of recipe " + str(i) + " is not below the " + str(tile_count) +
                   " records of " + section_kind_name(tiles));
        }
      zero(c, 24, r.reserved0);
      zero(c, 28, r.reserved1);
    }
  }

  void check_meshes() {
    const auto meshes = p_.records<SectionKind::meshes>();
    const std::uint64_t vertices = p_.record_count(SectionKind::vertex_positions);
    for (SectionKind k : {SectionKind::vertex_normals, SectionKind::vertex_uvs})
      if (p_.has(k) && p_.record_count(k) != vertices)
        throw PackageError(p_.name(), Rule::record_size, p_.locate(k, 0),
                           section_kind_name(k) + " has " + str(p_.record_count(k)) + " records for " + str(vertices) +
                               " vertex positions");
    // An empty triangle_drops is the same as none: no triangle drops a copy.
    for (SectionKind k : {SectionKind::triangle_shells, SectionKind::triangle_drops})
      if (p_.has(k) && (k != SectionKind::triangle_drops || p_.record_count(k) > 0) &&
          p_.record_count(k) != p_.record_count(SectionKind::triangles))
        throw PackageError(p_.name(), Rule::record_size, p_.locate(k, 0),
                           section_kind_name(k) + " has " + str(p_.record_count(k)) + " records for " +
                               str(p_.record_count(SectionKind::triangles)) + " triangles");
    const auto tris = p_.records<SectionKind::triangles>();
    for (std::uint64_t i = 0; i < meshes.size(); ++i) {
      const gpu::Mesh& m = meshes[i];
      const Cursor c = cursor<SectionKind::meshes>(i);
      ordered_aabb(c, 0, m.aabb_min, m.aabb_max);
      range(c, 32, m.first_vertex, m.vertex_count, SectionKind::vertex_positions, "vertex range");
      range(c, 40, m.first_triangle, m.triangle_count, SectionKind::triangles, "triangle range");
      for (std::uint64_t t = m.first_triangle; t < std::uint64_t{m.first_triangle} + m.triangle_count; ++t) {
        const std::uint32_t v[3] = {tris[t].v0, tris[t].v1, tris[t].v2};
        for (int k = 0; k < 3; ++k)
          if (v[k] >= m.vertex_count)
            fail(cursor<SectionKind::triangles>(t), 4 * k, Rule::index_out_of_range,
                 "vertex index " + str(v[k]) + " is not below mesh " + str(i) + "'s " + str(m.vertex_count) + " vertices");
      }
    }
  }

  void check_vertices() {
    const auto pos = p_.records<SectionKind::vertex_positions>();
    for (std::uint64_t i = 0; i < pos.size(); ++i) finite(cursor<SectionKind::vertex_positions>(i), 0, pos[i], "position");
    const auto nrm = p_.records<SectionKind::vertex_normals>();
    for (std::uint64_t i = 0; i < nrm.size(); ++i) finite(cursor<SectionKind::vertex_normals>(i), 0, nrm[i], "normal");
    const auto uvs = p_.records<SectionKind::vertex_uvs>();
    for (std::uint64_t i = 0; i < uvs.size(); ++i) finite(cursor<SectionKind::vertex_uvs>(i), 0, &uvs[i].x, 2, "UV");
  }

  void check_triangle_shells() {
    const auto shells = p_.records<SectionKind::triangle_shells>();
    for (std::uint64_t i = 0; i < shells.size(); ++i) {
      const gpu::TriangleShell& s = shells[i];
      const Cursor c = cursor<SectionKind::triangle_shells>(i);
      finite(c, 0, s.uv_min_max, "UV box");
      finite(c, 16, &s.h_plus, 3, "shell offset");
      if (s.uv_min_max.x > s.uv_min_max.z || s.uv_min_max.y > s.uv_min_max.w)
        fail(c, 0, Rule::inverted_aabb, "UV minimum exceeds maximum");
      if (s.h_plus < 0 || s.h_minus < 0 || s.side_offset < 0) fail(c, 16, Rule::bad_value, "negative shell offset");
      // Bits 0-2: edge k (corners k, k+1 mod 3) is a seam this triangle yields on; bits 3-5: corner k
      // touches such a seam of its chart (shared/seam.h).
      if ((s.seam_edges & ~63u) != 0)  // kSeamEdgeMask of shared/seam.h (not on nano_format's include path)
        fail(c, 28, Rule::bad_value, "seam_edges has bits beyond 0-5 set (" + str(s.seam_edges) + ")");
    }
  }

  // A compartment's tile set must lie in its tile section, and its recipe must be of the right
  // dimensionality and use only tiles of that set.
  void check_tile_set(const Cursor& c, std::uint64_t off, std::uint32_t first, std::uint32_t count, std::uint32_t recipe,
                      SectionKind tiles, std::uint32_t dimensionality) const {
    if (recipe == gpu::NANO_NO_INDEX) return;
    if (count == 0) fail(c, off + 4, Rule::bad_value, "empty tile set");
    range(c, off, first, count, tiles, "tile set");
    index(c, off + 8, recipe, SectionKind::recipes, "recipe");
    const gpu::Recipe& r = p_.records<SectionKind::recipes>()[recipe];
    if (r.dims.w != dimensionality) fail(c, off, Rule::bad_value, "recipe " + str(recipe) + " has the wrong dimensionality");
    const auto indices = p_.records<SectionKind::recipe_indices>();
    for (std::uint64_t k = r.first_index; k < std::uint64_t{r.first_index} + r.index_count; ++k)
      if (indices[k] < first || indices[k] - first >= count)
        fail(c, off, Rule::index_out_of_range,
             "recipe " + str(recipe) + " uses tile " + str(indices[k]) + " outside the tile set [" + str(first) + ", +" +
                 str(count) + ")");
  }

  void check_compartments() {
    const auto comps = p_.records<SectionKind::compartments>();
    for (std::uint64_t i = 0; i < comps.size(); ++i) {
      const gpu::Compartment& k = comps[i];
      const Cursor c = cursor<SectionKind::compartments>(i);
      finite(c, 0, k.grid_min, "core-grid origin");
      finite(c, 32, k.scales, "scales");
      index(c, 48, k.mesh, SectionKind::meshes, "mesh");
      check_tile_set(c, 52, k.membrane_first_tile, k.membrane_tile_count, k.membrane_recipe, SectionKind::tiles2d,
                     gpu::NANO_RECIPE_2D);
      check_tile_set(c, 64, k.soluble_first_tile, k.soluble_tile_count, k.soluble_recipe, SectionKind::tiles3d,
                     gpu::NANO_RECIPE_3D);
      if (k.membrane_recipe != gpu::NANO_NO_INDEX) {
        if (k.replication_width == 0 || k.replication_height == 0)
          fail(c, 76, Rule::bad_value, "replication area is empty");
        if (!(k.scales.x > 0) || !(k.scales.y > 0)) fail(c, 32, Rule::bad_value, "UV scale and tile size must be positive");
      }
      // scales.w: the shape factor of the smooth surface membrane copies stand on (format 2.3;
      // chart_smooth_position), 0 = flat facets (2.0-2.2, which reserved it as 0).
      if (!(k.scales.w >= 0 && k.scales.w <= 1)) fail(c, 44, Rule::bad_value, "scales.w (surface smoothness) must lie in [0, 1]");
      if (k.scales.w != 0 && p_.header().version_minor < 3)
        fail(c, 44, Rule::bad_value, "scales.w is reserved and must be 0 before format 2.3");
      if (k.soluble_recipe != gpu::NANO_NO_INDEX) {
        if (!(k.grid_min.w > 0)) fail(c, 12, Rule::bad_value, "box size is not positive");
        if (!(k.scales.z > 0)) fail(c, 40, Rule::bad_value, "cube size is not positive");
        if (k.grid_dims.x == 0 || k.grid_dims.y == 0 || k.grid_dims.z == 0) fail(c, 16, Rule::bad_value, "core grid is empty");
        const auto boxes = checked_mul(std::uint64_t{k.grid_dims.x} * k.grid_dims.y, k.grid_dims.z);
        if (!boxes || !range_within(k.grid_dims.w, *boxes, p_.record_count(SectionKind::occupancy)))
          fail(c, 28, Rule::index_out_of_range,
               "occupancy range of the core grid exceeds the " + str(p_.record_count(SectionKind::occupancy)) +
                   " bytes of section occupancy");
      }
      string_ref(c, 84, k.name_offset, k.name_length, "name");
      zero(c, 92, k.reserved0);
      if (k.soluble_recipe == gpu::NANO_NO_INDEX && k.core_masks.y != 0)
        fail(c, 100, Rule::bad_value, "boundary boxes without a core grid");
      range(c, 96, k.core_masks.x, k.core_masks.y, SectionKind::boundary_boxes, "boundary-box range");
      zero(c, 104, k.core_masks.z);
      zero(c, 108, k.core_masks.w);
    }
  }

  void check_occupancy() {
    const auto occ = p_.records<SectionKind::occupancy>();
    for (std::uint64_t i = 0; i < occ.size(); ++i)
      if (occ[i] > gpu::NANO_BOX_BOUNDARY)
        fail(cursor<SectionKind::occupancy>(i), 0, Rule::bad_value, "occupancy value " + str(occ[i]) + " is not 0, 1 or 2");
  }

  // The keep-masks of each core grid (ranges, grid and occupancy range already checked by
  // check_compartments): one sorted record per BOUNDARY box and nothing else, and W words per box,
  // W being fixed per compartment so a shader can index the words without finding the largest cube.
  void check_core_masks() {
    const auto comps = p_.records<SectionKind::compartments>();
    const auto cubes = p_.records<SectionKind::tiles3d>();
    const auto boxes = p_.records<SectionKind::boundary_boxes>();
    const auto words = p_.records<SectionKind::mask_words>();
    const auto occ = p_.records<SectionKind::occupancy>();
    for (std::uint64_t i = 0; i < comps.size(); ++i) {
      const gpu::Compartment& k = comps[i];
      if (k.soluble_recipe == gpu::NANO_NO_INDEX) continue;
      std::uint64_t largest = 0;
      for (std::uint64_t t = k.soluble_first_tile; t < std::uint64_t{k.soluble_first_tile} + k.soluble_tile_count; ++t)
        largest = std::max<std::uint64_t>(largest, cubes[t].instance_count);
      const std::uint64_t per_box = (largest + 31) / 32;
      const std::uint64_t cells = std::uint64_t{k.grid_dims.x} * k.grid_dims.y * k.grid_dims.z;
      const std::string whose = " of compartment " + str(i);
      for (std::uint64_t r = k.core_masks.x; r < std::uint64_t{k.core_masks.x} + k.core_masks.y; ++r) {
        const gpu::BoundaryBox& b = boxes[r];
        const Cursor c = cursor<SectionKind::boundary_boxes>(r);
        if (b.box >= cells)
          fail(c, 0, Rule::index_out_of_range, "box " + str(b.box) + " is not below the " + str(cells) + " boxes" + whose);
        const bool first = r == k.core_masks.x;
        if (!first && b.box <= boxes[r - 1].box)
          fail(c, 0, Rule::bad_value, "box " + str(b.box) + " does not follow box " + str(boxes[r - 1].box) + whose);
        if (occ[k.grid_dims.w + b.box] != gpu::NANO_BOX_BOUNDARY)
          fail(c, 0, Rule::bad_value, "box " + str(b.box) + whose + " is not a boundary box");
        if (!first && b.first_word != std::uint64_t{boxes[r - 1].first_word} + per_box)
          fail(c, 4, Rule::bad_value,
               "first word " + str(b.first_word) + " is not the previous box's plus " + str(per_box) + whose);
        if (!range_within(b.first_word, per_box, words.size()))
          fail(c, 4, Rule::index_out_of_range,
               "mask words [" + str(b.first_word) + ", +" + str(per_box) + ") exceed the " + str(words.size()) +
                   " records of mask_words");
        // Only the last word can hold bits past the largest cube; a reader counting kept copies
        // by popcount over the words would count them.
        const std::uint64_t last = b.first_word + per_box - 1;
        if (largest % 32 != 0 && words[last] >> (largest % 32) != 0)
          fail(cursor<SectionKind::mask_words>(last), 0, Rule::bad_value,
               "keep bit beyond the " + str(largest) + " molecules of the largest cube" + whose);
      }
      // Conversely every BOUNDARY box is listed: one merge pass over the grid's occupancy bytes.
      std::uint64_t next = k.core_masks.x;
      const std::uint64_t end = std::uint64_t{k.core_masks.x} + k.core_masks.y;
      for (std::uint64_t box = 0; box < cells; ++box) {
        if (occ[k.grid_dims.w + box] != gpu::NANO_BOX_BOUNDARY) continue;
        if (next == end || boxes[next].box != box)
          fail(cursor<SectionKind::occupancy>(k.grid_dims.w + box), 0, Rule::bad_value,
               "boundary box " + str(box) + whose + " has no record in boundary_boxes");
        ++next;
      }
    }
  }

  // The membrane copies the baker dropped (format 2.2): per triangle a strictly ascending key range,
  // every key naming a replication slot and an instance that the triangle's compartment can hold, so
  // a shader's binary search over a triangle's keys reads only that triangle's keys.
  void check_membrane_drops() {
    const auto drops = p_.records<SectionKind::triangle_drops>();
    if (drops.empty()) return;
    const auto keys = p_.records<SectionKind::dropped_copies>();
    for (std::uint64_t t = 0; t < drops.size(); ++t) {
      const Cursor c = cursor<SectionKind::triangle_drops>(t);
      range(c, 0, drops[t].first, drops[t].count, SectionKind::dropped_copies, "dropped-copy range");
      for (std::uint64_t k = std::uint64_t{drops[t].first} + 1; k < std::uint64_t{drops[t].first} + drops[t].count; ++k)
        if (keys[k] <= keys[k - 1])
          fail(cursor<SectionKind::dropped_copies>(k), 0, Rule::bad_value,
               "key " + str(keys[k]) + " does not follow key " + str(keys[k - 1]) + " of triangle " + str(t));
    }
    // What the keys may name: per mesh, the smallest replication area and tile set among the
    // compartments wearing a membrane on it; a mesh without a membrane drops nothing.
    const auto meshes = p_.records<SectionKind::meshes>();
    const auto comps = p_.records<SectionKind::compartments>();
    const auto squares = p_.records<SectionKind::tiles2d>();
    std::vector<std::uint64_t> slots(meshes.size(), 0), instances(meshes.size(), 0);
    std::vector<bool> seen(meshes.size(), false);
    for (const gpu::Compartment& k : comps) {
      if (k.membrane_recipe == gpu::NANO_NO_INDEX) continue;
      std::uint64_t largest = 0;
      for (std::uint64_t i = k.membrane_first_tile; i < std::uint64_t{k.membrane_first_tile} + k.membrane_tile_count; ++i)
        largest = std::max<std::uint64_t>(largest, squares[i].instance_count);
      const std::uint64_t area = std::uint64_t{k.replication_width} * k.replication_height;
      slots[k.mesh] = seen[k.mesh] ? std::min(slots[k.mesh], area) : area;
      instances[k.mesh] = seen[k.mesh] ? std::min(instances[k.mesh], largest) : largest;
      seen[k.mesh] = true;
    }
    constexpr std::uint64_t kInstanceLimit = std::uint64_t{1} << gpu::NANO_DROP_INSTANCE_BITS;
    for (std::uint64_t m = 0; m < meshes.size(); ++m) {
      const std::uint64_t slot_limit = std::min(slots[m], std::uint64_t{1} << (32 - gpu::NANO_DROP_INSTANCE_BITS));
      const std::uint64_t instance_limit = std::min(instances[m], kInstanceLimit);
      for (std::uint64_t t = meshes[m].first_triangle; t < std::uint64_t{meshes[m].first_triangle} + meshes[m].triangle_count; ++t)
        for (std::uint64_t k = drops[t].first; k < std::uint64_t{drops[t].first} + drops[t].count; ++k) {
          const std::uint64_t slot = keys[k] >> gpu::NANO_DROP_INSTANCE_BITS, instance = keys[k] & (kInstanceLimit - 1);
          if (slot >= slot_limit || instance >= instance_limit)
            fail(cursor<SectionKind::dropped_copies>(k), 0, Rule::index_out_of_range,
                 "key " + str(keys[k]) + " of triangle " + str(t) + " names slot " + str(slot) + ", instance " +
                     str(instance) + "; mesh " + str(m) + " holds " + str(slot_limit) + " slots of at most " +
                     str(instance_limit) + " instances");
        }
    }
  }

  // Empty-space skipping (format 2.7): exactly the levels format/core_skip.cpp derives from the
  // grids' occupancy, cubes and keep-masks (checked above), so a skipped block never hides a copy.
  void check_core_skip() {
    if (p_.record_count(SectionKind::core_skip) == 0) return;  // absent or empty: the runtime derives it
    const auto comps = p_.records<SectionKind::compartments>();
    const auto skip = p_.records<SectionKind::core_skip>();
    const CoreGridRecords grids{comps,
                                p_.records<SectionKind::occupancy>(),
                                p_.records<SectionKind::tiles3d>(),
                                p_.records<SectionKind::recipes>(),
                                p_.records<SectionKind::recipe_indices>(),
                                p_.records<SectionKind::boundary_boxes>(),
                                p_.records<SectionKind::mask_words>()};
    const CoreSkipLayout layout = core_skip_layout(comps);
    if (skip.size() != (layout.cells + 1) / 2)
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::core_skip, 0),
                         "core_skip has " + str(skip.size()) + " bytes, not the " + str((layout.cells + 1) / 2) +
                             " that hold the " + str(layout.cells) + " cells of the widened core grids");
    const std::vector<std::uint8_t> expected = core_skip_section(grids);
    const auto [mine, theirs] = std::mismatch(expected.begin(), expected.end(), skip.begin());
    if (mine == expected.end()) return;
    const std::uint64_t byte = std::uint64_t(mine - expected.begin());
    const std::uint64_t cell = 2 * byte + ((*mine & 0x0F) == (*theirs & 0x0F) ? 1 : 0);
    const auto level = [&](std::uint8_t b) { return str((b >> (4 * (cell % 2))) & 0x0F); };
    std::uint64_t ci = 0;
    while (ci < comps.size() && (layout.first_cell[ci] == kNoCoreGrid || layout.first_cell[ci] > cell ||
                                 cell - layout.first_cell[ci] >= core_skip_cell_count(comps[ci])))
      ++ci;
    if (ci == comps.size())
      fail(cursor<SectionKind::core_skip>(byte), 0, Rule::bad_value, "the padding after the last cell is " + level(*theirs) + ", not 0");
    const std::uint64_t local = cell - layout.first_cell[ci];
    const glm::uvec3 n = core_skip_cells(comps[ci]);
    fail(cursor<SectionKind::core_skip>(byte), 0, Rule::bad_value,
         "skip level " + level(*theirs) + " of cell (" + str(local % n.x) + ", " + str(local / n.x % n.y) + ", " +
             str(local / (std::uint64_t{n.x} * n.y)) + ") of compartment " + str(ci) + "'s widened core grid is not " +
             level(*mine) + ", the level its boxes give");
  }

  // The medium (format 2.8): its region, cube set and recipe, and the molecules of its cubes within
  // one box of their own (the renderer's walk looks one box around each cell); one exclusion field
  // per compartment, each inside exclusion_values with finite values within its clamp. The shader
  // indexes fields by compartment and values by node, so both are checked here.
  void check_medium() {
    const auto media = p_.records<SectionKind::medium>();
    const auto fields = p_.records<SectionKind::exclusion_fields>();
    const auto values = p_.records<SectionKind::exclusion_values>();
    if (media.size() > 1)
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::medium, 0),
                         "medium has " + str(media.size()) + " records; a package holds at most one medium");
    const std::uint64_t compartments = p_.record_count(SectionKind::compartments);
    if (!fields.empty() && fields.size() != compartments)
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::exclusion_fields, 0),
                         "exclusion_fields has " + str(fields.size()) + " records for " + str(compartments) + " compartments");
    if (!media.empty() && fields.empty() && compartments > 0)
      throw PackageError(p_.name(), Rule::missing_section, p_.locate(SectionKind::medium, 0),
                         "a medium needs one exclusion field per compartment; exclusion_fields is empty");
    for (std::uint64_t i = 0; i < fields.size(); ++i) {
      const gpu::ExclusionField& f = fields[i];
      const Cursor c = cursor<SectionKind::exclusion_fields>(i);
      finite(c, 0, f.origin, "field origin and spacing");
      finite(c, 32, f.limits, "field limits");
      if (!(f.origin.w > 0)) fail(c, 12, Rule::bad_value, "node spacing is not positive");
      if (f.dims.x < 2 || f.dims.y < 2 || f.dims.z < 2) fail(c, 16, Rule::bad_value, "a field needs at least 2 nodes per axis");
      const auto nodes = checked_mul(std::uint64_t{f.dims.x} * f.dims.y, f.dims.z);
      if (!nodes) fail(c, 16, Rule::index_out_of_range, "node count overflows");
      range(c, 28, f.dims.w, *nodes, SectionKind::exclusion_values, "node values");
      if (!(f.limits.x >= 0)) fail(c, 32, Rule::bad_value, "margin is negative");
      if (!(f.limits.y > f.limits.x)) fail(c, 36, Rule::bad_value, "clamp does not exceed the margin");
      if (f.limits.z != 1.0f / f.origin.w) fail(c, 40, Rule::bad_value, "limits.z is not 1 / spacing");
      zero(c, 44, f.limits.w != 0.0f);
      for (std::uint64_t n = f.dims.w; n < f.dims.w + *nodes; ++n)
        if (!(std::abs(values[n]) <= f.limits.y))
          fail(cursor<SectionKind::exclusion_values>(n), 0, Rule::bad_value,
               "value " + std::to_string(values[n]) + " of exclusion field " + str(i) + " is not within its clamp ±" +
                   std::to_string(f.limits.y));
    }
    if (media.empty()) return;
    const gpu::Medium& m = media[0];
    const Cursor c = cursor<SectionKind::medium>(0);
    finite(c, 0, m.region_min, "region minimum and box edge");
    finite(c, 16, m.region_max, "region maximum and clearance");
    const float B = m.region_min.w;
    if (!(B > 0)) fail(c, 12, Rule::bad_value, "box edge is not positive");
    if (!(m.region_max.w >= 0)) fail(c, 28, Rule::bad_value, "clearance is negative");
    if (m.boxes.x == 0 || m.boxes.y == 0 || m.boxes.z == 0) fail(c, 32, Rule::bad_value, "the region has no box");
    for (int a = 0; a < 3; ++a)
      if (!(m.region_max[a] >= m.region_min[a] + float(m.boxes[a]) * B * (1.0f - 1e-6f)))
        fail(c, 16 + 4 * a, Rule::bad_value, "region maximum on axis " + str(a) + " is below its boxes' extent");
    // Copy numbers: boxes · I below 2^60 (format/validator and placement share the 64-bit space).
    const auto boxes = checked_mul(std::uint64_t{m.boxes.x} * m.boxes.y, m.boxes.z);
    if (!boxes || *boxes > (std::uint64_t{1} << 50)) fail(c, 32, Rule::bad_value, "the region has more than 2^50 boxes");
    check_tile_set(c, 48, m.tiles.x, m.tiles.y, m.boxes.w, SectionKind::tiles3d, gpu::NANO_RECIPE_3D);
    if (m.boxes.w == gpu::NANO_NO_INDEX) fail(c, 44, Rule::bad_value, "a medium needs a recipe");
    zero(c, 60, m.tiles.w);
    const auto cubes = p_.records<SectionKind::tiles3d>();
    const auto instances = p_.records<SectionKind::instances>();
    const auto molecules = p_.records<SectionKind::molecules>();
    std::uint32_t largest = 0;
    for (std::uint64_t t = m.tiles.x; t < std::uint64_t{m.tiles.x} + m.tiles.y; ++t) {
      largest = std::max(largest, cubes[t].instance_count);
      for (std::uint64_t k = cubes[t].first_instance; k < std::uint64_t{cubes[t].first_instance} + cubes[t].instance_count; ++k) {
        const gpu::MoleculeInstance& mi = instances[k];
        const float r = molecules[mi.molecule_type].aabb_min.w;
        for (int a = 0; a < 3; ++a)
          if (!(mi.position[a] - r >= -B && mi.position[a] + r <= 2.0f * B))
            fail(cursor<SectionKind::instances>(k), 16 + 4 * a, Rule::bad_value,
                 "a molecule of the medium's cube " + str(t) + " reaches beyond the boxes next to its own");
      }
    }
    if (m.tiles.z != largest)
      fail(c, 56, Rule::bad_value, "largest instance count " + str(m.tiles.z) + " is not the cube set's " + str(largest));
  }

  // The level of detail (format 2.5): per molecule type a non-empty range of beads that together
  // merge exactly its atoms, each bead a finite sphere inside the type's box holding the atom it
  // reports, which is one of the type's. The renderer trusts these indices and boxes.
  void check_beads() {
    if (p_.record_count(SectionKind::beads) == 0 && p_.record_count(SectionKind::bead_ranges) == 0) return;
    const auto mols = p_.records<SectionKind::molecules>();
    const auto ranges = p_.records<SectionKind::bead_ranges>();
    if (ranges.size() != mols.size())
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::bead_ranges, 0),
                         "bead_ranges has " + str(ranges.size()) + " records for " + str(mols.size()) + " molecule types");
    const auto beads = p_.records<SectionKind::beads>();
    const auto atoms = p_.records<SectionKind::atoms>();
    for (std::uint64_t t = 0; t < ranges.size(); ++t) {
      const Cursor rc = cursor<SectionKind::bead_ranges>(t);
      if (ranges[t].count == 0) fail(rc, 4, Rule::bad_value, "molecule type " + str(t) + " has no beads");
      range(rc, 0, ranges[t].first, ranges[t].count, SectionKind::beads, "bead range");
      const gpu::MoleculeType& m = mols[t];
      std::uint64_t merged = 0;
      for (std::uint64_t b = ranges[t].first; b < std::uint64_t{ranges[t].first} + ranges[t].count; ++b) {
        const gpu::Bead& bead = beads[b];
        const Cursor c = cursor<SectionKind::beads>(b);
        finite(c, 0, bead.centre_radius, "bead");
        if (!(bead.centre_radius.w > 0)) fail(c, 12, Rule::bad_value, "bead radius is not positive");
        const glm::vec3 centre(bead.centre_radius);
        const float slack = 1e-3f * (1.0f + m.aabb_min.w);
        for (int a = 0; a < 3; ++a)
          if (centre[a] < m.aabb_min[a] - slack || centre[a] > m.aabb_max[a] + slack)
            fail(c, 4 * a, Rule::bad_value, "bead centre lies outside molecule type " + str(t) + "'s box");
        if (bead.atom < m.first_atom || bead.atom - m.first_atom >= m.atom_count)
          fail(c, 16, Rule::index_out_of_range,
               "atom " + str(bead.atom) + " is not one of molecule type " + str(t) + "'s atoms [" + str(m.first_atom) +
                   ", +" + str(m.atom_count) + ")");
        const glm::vec4 atom = atoms[bead.atom].centre_radius;
        if (glm::length(glm::vec3(atom) - centre) + atom.w > bead.centre_radius.w + slack)
          fail(c, 12, Rule::bad_value, "bead does not hold the sphere of the atom it reports");
        if (bead.atom_count == 0) fail(c, 20, Rule::bad_value, "bead merges no atom");
        merged += bead.atom_count;
        zero(c, 24, bead.reserved0);
        zero(c, 28, bead.reserved1);
      }
      if (merged != m.atom_count)
        fail(rc, 0, Rule::bad_value,
             "the beads of molecule type " + str(t) + " merge " + str(merged) + " atoms, not its " + str(m.atom_count));
    }
  }

  void check_scene() {
    const auto scene = p_.records<SectionKind::scene>();
    if (!p_.has(SectionKind::scene)) return;
    if (scene.size() != 1)
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::scene, 0),
                         "section scene must hold exactly one record, not " + str(scene.size()));
    const gpu::SceneSettings& s = scene[0];
    const Cursor c = cursor<SectionKind::scene>(0);
    finite(c, 0, s.camera_position, "camera position");
    finite(c, 16, s.camera_look_at, "camera look_at");
    finite(c, 32, s.camera_up, "camera up");
    if (!(s.camera_position.w > 0 && s.camera_position.w < 3.14159265f)) fail(c, 12, Rule::bad_value, "field of view outside (0, pi)");
    zero(c, 52, s.reserved0);
    zero(c, 56, s.reserved1);
    zero(c, 60, s.reserved2);
  }

  void check_compartment_instances() {
    const auto inst = p_.records<SectionKind::compartment_instances>();
    for (std::uint64_t i = 0; i < inst.size(); ++i) {
      const Cursor c = cursor<SectionKind::compartment_instances>(i);
      for (int row = 0; row < 3; ++row) finite(c, 16 * row, inst[i].transform[row], "transform");
      index(c, 48, inst[i].compartment, SectionKind::compartments, "compartment");
      zero(c, 52, inst[i].reserved0);
      zero(c, 56, inst[i].reserved1);
      zero(c, 60, inst[i].reserved2);
    }
  }

  // |v| within 1e-3 of 1: the baker normalises in double and stores floats.
  void unit(const Cursor& c, std::uint64_t off, const glm::vec3& v, const char* what) const {
    if (!(std::abs(glm::length(v) - 1.0f) <= 1e-3f)) fail(c, off, Rule::bad_value, std::string(what) + " is not a unit vector");
  }
  void zero_vec(const Cursor& c, std::uint64_t off, const vec4& v, int from, const char* what) const {
    for (int i = from; i < 4; ++i)
      if (v[i] != 0.0f) fail(c, off + 4 * i, Rule::nonzero_reserved, std::string(what) + ": reserved member is not zero");
  }

  // Only the parameters of effects the flags turn on may be non-zero, and those must make sense:
  // the renderer feeds them to the shader unchecked.
  void check_effects() {
    if (p_.record_count(SectionKind::effects) == 0) return;  // absent or empty: every effect off
    const auto effects = p_.records<SectionKind::effects>();
    if (effects.size() != 1)
      throw PackageError(p_.name(), Rule::record_size, p_.locate(SectionKind::effects, 0),
                         "section effects must hold exactly one record, not " + str(effects.size()));
    const std::uint32_t flags = p_.has(SectionKind::scene) && p_.record_count(SectionKind::scene) == 1
                                    ? p_.records<SectionKind::scene>()[0].effect_flags : 0u;
    const gpu::SceneEffects& e = effects[0];
    const Cursor c = cursor<SectionKind::effects>(0);
    const auto* floats = reinterpret_cast<const float*>(&e);
    finite(c, 0, floats, 60, "effect parameter");
    const bool clipping = flags & package_flag(EffectId::clipping);
    if (e.clip_plane_count > gpu::NANO_MAX_CLIP_PLANES || (!clipping && e.clip_plane_count != 0))
      fail(c, 240, Rule::bad_value, "clip_plane_count " + str(e.clip_plane_count) + (clipping ? " exceeds 8" : " with clipping off"));
    for (std::uint32_t k = 0; k < gpu::NANO_MAX_CLIP_PLANES; ++k) {
      if (k < e.clip_plane_count) unit(c, 16 * k, glm::vec3(e.clip_planes[k]), "clip plane normal");
      else zero_vec(c, 16 * k, e.clip_planes[k], 0, "unused clip plane");
    }
    if (e.clip_box_min.w == 1.0f && clipping) {
      for (int a = 0; a < 3; ++a)
        if (!(e.clip_box_min[a] < e.clip_box_max[a])) fail(c, 128 + 4 * a, Rule::inverted_aabb, "clip box minimum not below maximum");
    } else if (e.clip_box_min != vec4(0.0f) || e.clip_box_max != vec4(0.0f)) {
      fail(c, 140, Rule::bad_value, "clip box flag must be 1 (box on, with clipping) or the box all zero");
    }
    zero_vec(c, 144, e.clip_box_max, 3, "clip box maximum");
    const bool keyed = p_.record_count(SectionKind::keyframes) > 0;
    if ((flags & package_flag(EffectId::animation)) && !keyed) {
      if (e.spin.w != 0.0f) unit(c, 160, glm::vec3(e.spin), "spin axis");
    } else if (e.spin != vec4(0.0f) || e.velocity != vec4(0.0f)) {
      fail(c, 160, Rule::bad_value, "steady motion without the animation flag, or beside keyframes");
    }
    zero_vec(c, 176, e.velocity, 3, "velocity");
    check_effect_parameters(c, e, flags);
  }

  // The table's plain parameters (common/effect_table.hpp): in range while their effect is on, zero
  // while it is off. Every word that neither they nor clipping's and proxy motion's members (checked
  // above) own is reserved and must be zero.
  void check_effect_parameters(const Cursor& c, const gpu::SceneEffects& e, std::uint32_t flags) const {
    constexpr std::size_t kWords = sizeof(gpu::SceneEffects) / 4;
    std::array<bool, kWords> owned{};
    const auto own = [&](std::size_t offset, std::size_t bytes) {
      for (std::size_t w = offset / 4; w < (offset + bytes) / 4; ++w) owned[w] = true;
    };
    own(offsetof(gpu::SceneEffects, clip_planes), offsetof(gpu::SceneEffects, clip_box_max) + 12);  // clip box max .w is reserved
    own(offsetof(gpu::SceneEffects, spin), 16);
    own(offsetof(gpu::SceneEffects, velocity), 12);  // velocity .w is reserved
    own(offsetof(gpu::SceneEffects, clip_plane_count), 4);
    std::array<std::uint32_t, kWords> words;
    std::memcpy(words.data(), &e, sizeof e);
    for (const EffectDeclaration& effect : effect_table()) {
      const bool on = (flags & effect.package_flag) != 0;
      for (std::size_t i = 0; i < effect.parameters.size(); ++i) {
        const EffectParameter& p = effect.parameters[i];
        const std::uint32_t first = p.record_offset / 4, count = p.kind == ParameterKind::unit_vector ? 3 : 1;
        const std::string what = std::string(effect.name) + " " + std::string(p.key);
        for (std::uint32_t w = first; w < first + count; ++w) {
          owned[w] = true;
          if (!on && words[w] != 0) fail(c, 4 * w, Rule::nonzero_reserved, what + " is set while " + std::string(effect.name) + " is off");
        }
        if (!on) continue;
        if (p.kind == ParameterKind::unit_vector) {
          unit(c, p.record_offset, direction_slot(e, p), what.c_str());
        } else if (p.kind == ParameterKind::colour) {
          if (colour_slot(e, p) >> 24 != 255u) fail(c, p.record_offset, Rule::bad_value, what + ": a colour's alpha byte must be 255");
        } else if (const std::string problem = parameter_problem(p, glm::dvec3(number_slot(e, p), 0.0, 0.0)); !problem.empty()) {
          fail(c, p.record_offset, Rule::bad_value, what + " " + problem);
        }
      }
    }
    for (std::size_t w = 0; w < kWords; ++w)
      if (!owned[w] && words[w] != 0) fail(c, 4 * w, Rule::nonzero_reserved, "effects record: reserved member is not zero");
  }

  void check_keyframes() {
    const auto keys = p_.records<SectionKind::keyframes>();
    for (std::uint64_t i = 0; i < keys.size(); ++i) {
      const gpu::InstanceKeyframe& k = keys[i];
      const Cursor c = cursor<SectionKind::keyframes>(i);
      for (int row = 0; row < 3; ++row) finite(c, 16 * row, k.transform[row], "transform");
      const glm::dmat3 linear(glm::dvec3(k.transform[0]), glm::dvec3(k.transform[1]), glm::dvec3(k.transform[2]));
      if (!(std::abs(glm::determinant(linear)) > 1e-12)) fail(c, 0, Rule::bad_value, "transform is singular");
      if (!(std::isfinite(k.time) && k.time >= 0.0f)) fail(c, 48, Rule::bad_value, "time must be finite and ≥ 0");
      index(c, 52, k.instance, SectionKind::compartment_instances, "instance");
      if (i > 0 && (k.instance < keys[i - 1].instance || (k.instance == keys[i - 1].instance && !(k.time > keys[i - 1].time))))
        fail(c, 48, Rule::bad_value, "keyframes must ascend by (instance, time) with strictly increasing times");
      zero(c, 56, k.reserved0);
      zero(c, 60, k.reserved1);
    }
  }

  void check_provenance() {
    const auto text = p_.records<SectionKind::provenance>();
    for (std::uint64_t i = 0; i < text.size(); ++i)
      if (text[i] == '\0') fail(cursor<SectionKind::provenance>(i), 0, Rule::bad_value, "NUL byte in provenance text");
  }

  const Package& p_;
};

}  // namespace

void validate_semantics(const Package& package) { SemanticCheck(package).run(); }

Package open_validated(const std::filesystem::path& path) {
  Package p = Package::open(path);
  validate_semantics(p);
  return p;
}

}  // namespace nano::format
