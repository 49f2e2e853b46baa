#include "runtime/render/levels/membrane.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include <glm/gtc/quaternion.hpp>

#include "runtime/placement/membrane_distortion.hpp"
#include "runtime/render/levels/scene_state.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"
#include "shared/quaternion.h"
#include "shared/shell_prism.h"

namespace nano::levels {
namespace {

using glm::dmat3;
using glm::dvec3;
using glm::vec3;

// The shell offsets of the chosen mode, parallel to section triangle_shells.
std::vector<gpu::TriangleShell> mode_shells(const SceneState& s) {
  std::vector<gpu::TriangleShell> out(s.triangle_shells.begin(), s.triangle_shells.end());
  const bool fixed = s.options.shell == render::ShellMode::fixed || s.options.shell == render::ShellMode::fixed_overlap;
  const bool overlap = s.options.shell == render::ShellMode::adaptive_overlap || s.options.shell == render::ShellMode::fixed_overlap;
  for (const gpu::Mesh& mesh : s.meshes) {
    gpu::ShellOffsets largest{0, 0, 0};
    for (std::uint32_t t = mesh.first_triangle; t < mesh.first_triangle + mesh.triangle_count; ++t)
      largest = gpu::shell_offsets_max(largest, {out[t].h_plus, out[t].h_minus, out[t].side_offset});
    for (std::uint32_t t = mesh.first_triangle; t < mesh.first_triangle + mesh.triangle_count; ++t) {
      gpu::TriangleShell& shell = out[t];
      if (shell.h_plus == 0 && shell.h_minus == 0 && shell.side_offset == 0) continue;  // owns nothing: no prism
      if (fixed) shell.h_plus = largest.h_plus, shell.h_minus = largest.h_minus, shell.side_offset = largest.side;
      if (!overlap) shell.side_offset = 0;
    }
  }
  return out;
}

// One triangle's distortion (placement/membrane_distortion.hpp), or nothing for one that owns no copy.
std::optional<placement::MembraneDistortion> triangle_distortion(const SceneState& s, const gpu::Compartment& c,
                                                                 const gpu::RenderCompartment& rc, std::uint32_t t) {
  const gpu::Triangle& tri = s.triangles[t];
  const std::uint32_t f = s.meshes[c.mesh].first_vertex;
  placement::MembraneTriangleCorners corners;
  const std::uint32_t v[3] = {tri.v0, tri.v1, tri.v2};
  for (int i = 0; i < 3; ++i) {
    corners.position[i] = vec3(s.vertex_positions[f + v[i]]);
    corners.normal[i] = vec3(s.vertex_normals[f + v[i]]);
    corners.uv[i] = s.vertex_uvs[f + v[i]];
  }
  return placement::triangle_distortion(corners, {rc.membrane.x, rc.membrane.y, rc.membrane.z, c.scales.w});
}

placement::DistortionClasses distortion_classes(const SceneState& s, const gpu::Compartment& c, const gpu::RenderCompartment& rc) {
  const gpu::Mesh& mesh = s.meshes[c.mesh];
  std::vector<std::optional<placement::MembraneDistortion>> per(mesh.triangle_count);
  for (std::uint32_t k = 0; k < mesh.triangle_count; ++k) per[k] = triangle_distortion(s, c, rc, mesh.first_triangle + k);
  return placement::distortion_classes(per, rc.membrane.z);
}

// The M1-placed atoms of copy `m` (spheres included) as a box about its origin, from the atoms
// themselves (the instance's stored AABB is not trusted for what the renderer may skip).
std::pair<dvec3, dvec3> placed_extent(const SceneState& s, const gpu::MoleculeInstance& m) {
  const gpu::MoleculeType& type = s.molecules[m.molecule_type];
  const glm::dquat q(double(m.rotation.w), double(m.rotation.x), double(m.rotation.y), double(m.rotation.z));
  const dmat3 r = glm::mat3_cast(glm::normalize(q));
  dvec3 lo(INFINITY), hi(-INFINITY);
  for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
    const dvec3 p = r * dvec3(vec3(s.atoms[a].centre_radius));
    const double radius = s.atoms[a].centre_radius.w;
    lo = glm::min(lo, p - radius), hi = glm::max(hi, p + radius);
  }
  return {lo, hi};
}

// Square t's molecule boxes in the sheared tile space of distortion d (copy_boxes). Grows
// square_reach[t] to hold the copies in unsheared tile space.
std::vector<VkAabbPositionsKHR> square_boxes(SceneState& s, std::uint32_t t, const placement::MembraneDistortion& d, double half) {
  std::vector<VkAabbPositionsKHR> boxes;
  for (std::uint32_t m = s.tiles2d[t].first_instance; m < s.tiles2d[t].first_instance + s.tiles2d[t].instance_count; ++m) {
    const auto [atoms_lo, atoms_hi] = placed_extent(s, s.instances[m]);
    const placement::CopyBoxes b = placement::copy_boxes(dvec3(s.instances[m].position), (atoms_lo + atoms_hi) * 0.5, (atoms_hi - atoms_lo) * 0.5,
                                   s.type_radius[s.instances[m].molecule_type], d, half);
    boxes.push_back(box_of(b.lo, b.hi));
    s.square_reach[t].first = glm::min(s.square_reach[t].first, b.reach_lo);
    s.square_reach[t].second = glm::max(s.square_reach[t].second, b.reach_hi);
  }
  return boxes;
}

// The level record of square t's mLAS for distortion class k: class 0's at first_square, the other
// classes' after the beads'.
std::uint32_t square_level(const SceneState& s, std::uint32_t k, std::uint32_t t) {
  return k == 0 ? s.first_square + t : s.first_class_square + (k - 1) * std::uint32_t(s.tiles2d.size()) + t;
}

// mLAS per Wang square and distortion class: molecule boxes in tile space widened by the distortion
// of every compartment that uses the square. Writes each compartment's per-triangle class words.
void build_squares(SceneState& s) {
  std::vector<std::array<std::optional<placement::MembraneDistortion>, placement::kDistortionClasses>> square_distortion(s.tiles2d.size());
  std::vector<double> square_half(s.tiles2d.size(), 0.0);  // the tile point of its lift planes
  for (std::uint32_t ci = 0; ci < s.compartments.size(); ++ci) {
    const gpu::Compartment& c = s.compartments[ci];
    if (c.membrane_recipe == gpu::NANO_NO_INDEX) continue;
    const placement::DistortionClasses classes = distortion_classes(s, c, s.render_compartments[ci]);
    // Per triangle, where its class's squares start, relative to class 0's (frame.levels.x).
    s.render_compartments[ci].core_skip.y = std::uint32_t(s.orders.size());
    for (std::size_t k = 0; k < classes.of_triangle.size(); ++k)
      s.orders.push_back((square_level(s, classes.of_triangle[k], 0) - s.first_square) |
                         (classes.unsheared[k] ? gpu::NANO_LIFT_UNSHEARED : 0u));
    for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t) {
      // A square belongs to one membrane's tile set, so every compartment using it has its tile size.
      square_half[t] = s.render_compartments[ci].membrane.z;
      for (std::uint32_t k = 0; k < placement::kDistortionClasses; ++k) {
        if (classes.bound[k]) placement::widen_to(square_distortion[t][k], *classes.bound[k]);
      }
    }
  }
  s.square_reach.assign(s.tiles2d.size(), {dvec3(INFINITY), dvec3(-INFINITY)});
  for (std::uint32_t t = 0; t < s.tiles2d.size(); ++t)
    for (std::uint32_t k = 0; k < placement::kDistortionClasses; ++k)
      if (square_distortion[t][k] && s.tiles2d[t].instance_count > 0)  // else no compartment renders it
        s.add_tile_level(square_level(s, k, t), square_boxes(s, t, *square_distortion[t][k], square_half[t]));
}

// repLAS per compartment: its W×H replication slots as boxes in the space of the area's origin tile
// (slot (i, j) holds the union of the set's molecule boxes moved by (i·S, j·S)); orders hold the
// slot index i + W·j. Every tile of a triangle shares M1's linear part, so one query finds the slots.
void build_replication_areas(SceneState& s) {
  for (std::uint32_t ci = 0; ci < s.compartments.size(); ++ci) {
    const gpu::Compartment& c = s.compartments[ci];
    s.render_compartments[ci].span.w = gpu::NANO_NO_INDEX;
    if (c.membrane_recipe == gpu::NANO_NO_INDEX) continue;
    dvec3 lo(INFINITY), hi(-INFINITY);
    for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t)
      lo = glm::min(lo, s.square_reach[t].first), hi = glm::max(hi, s.square_reach[t].second);
    if (!(lo.x <= hi.x)) continue;  // no molecules
    const double S = c.scales.y;
    std::vector<VkAabbPositionsKHR> boxes;
    std::vector<std::uint32_t> slots;
    for (std::uint32_t j = 0; j < c.replication_height; ++j)
      for (std::uint32_t i = 0; i < c.replication_width; ++i) {
        const dvec3 shift(i * S, j * S, 0.0);
        boxes.push_back(box_of(lo + shift, hi + shift));
        slots.push_back(i + c.replication_width * j);
      }
    s.levels[s.first_area + ci] = s.build_level(boxes, slots, s.first_area + ci, s.report.memory.mlas);
    s.render_compartments[ci].span.w = s.first_area + ci;
    s.large_replication_areas = s.large_replication_areas || slots.size() > gpu::NANO_DIRECT_SLOTS;
    const VkAabbPositionsKHR slot = box_of(lo, hi);
    s.render_compartments[ci].slot_lo = glm::vec4(slot.minX, slot.minY, slot.minZ, float(S));
    s.render_compartments[ci].slot_hi = glm::vec4(slot.maxX, slot.maxY, slot.maxZ, 0.f);
  }
}

// The paper's two-level design for membranes: per Wang square one BLAS of every atom of every
// molecule, at its tile-space position p + R(q)·a (the affine tile placement, not the true M2:
// measured against the oracle by verify). orders hold (molecule index in the tile, atom index).
void build_atom_squares(SceneState& s) {
  for (std::uint32_t t = 0; t < s.tiles2d.size(); ++t) {
    if (s.level_records[s.first_square + t].count == 0) continue;  // no compartment renders it
    std::vector<VkAabbPositionsKHR> boxes;
    std::vector<std::uint32_t> values;
    for (std::uint32_t m = 0; m < s.tiles2d[t].instance_count; ++m) {
      const gpu::MoleculeInstance& mi = s.instances[s.tiles2d[t].first_instance + m];
      const gpu::MoleculeType& type = s.molecules[mi.molecule_type];
      for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
        const dvec3 c = dvec3(mi.position) + dvec3(gpu::quat_rotate(mi.rotation, vec3(s.atoms[a].centre_radius)));
        const double r = s.atoms[a].centre_radius.w + 1e-3;
        boxes.push_back(box_of(c - r, c + r));
        values.push_back(m);
        values.push_back(a);
      }
    }
    s.levels[s.first_atom_square + t] = s.build_level(boxes, values, s.first_atom_square + t, s.report.memory.mlas, 2);
  }
}

}  // namespace

void plan_membrane(SceneState& s, std::uint32_t ci) {
  const gpu::Compartment& c = s.compartments[ci];
  if (c.membrane_recipe == gpu::NANO_NO_INDEX) return;
  gpu::RenderCompartment& rc = s.render_compartments[ci];
  if (s.triangle_shells.empty())
    s.fail("compartments[" + std::to_string(ci) + "]", "has a membrane but the package has no triangle_shells: the shell renderer needs its prisms");
  const float S = c.scales.y;
  const float tile_uv = S / c.scales.x;
  rc.membrane.x = tile_uv;
  rc.membrane.y = tile_uv / S;
  rc.membrane.z = 0.5f * S;  // the tile point its lift plane is taken at (chart_smooth_lift_plane)
  std::uint32_t largest = 0;
  for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t)
    largest = std::max(largest, s.tiles2d[t].instance_count);
  rc.counts.x = largest;
  const std::uint64_t span =
      std::uint64_t{s.meshes[c.mesh].triangle_count} * c.replication_width * c.replication_height * largest;
  rc.span.x = std::uint32_t(span), rc.span.y = std::uint32_t(span >> 32);
}

void build_membrane(SceneState& s) {
  s.shell_records = mode_shells(s);
  s.shell_buffer = s.storage(std::as_bytes(std::span(s.shell_records)));
  s.report.memory.derived += s.shell_buffer.size();
  build_squares(s);
  build_replication_areas(s);
  if (s.options.two_level_membranes) build_atom_squares(s);
}

void write_membrane_descriptors(const SceneState& s, VkDescriptorSet set) {
  vk::write_storage_buffer(s.device.handle(), set, gpu::NANO_B_TRIANGLE_SHELLS, s.shell_buffer);
}

void membrane_prisms(const SceneState& s, std::uint32_t ci, std::vector<VkAabbPositionsKHR>& prisms,
                     std::vector<std::uint32_t>& prism_triangles) {
  const gpu::Compartment& c = s.compartments[ci];
  if (c.membrane_recipe == gpu::NANO_NO_INDEX) return;
  const gpu::Mesh& mesh = s.meshes[c.mesh];
  const std::uint32_t f = mesh.first_vertex;
  for (std::uint32_t tl = 0; tl < mesh.triangle_count; ++tl) {
    const gpu::TriangleShell& shell = s.shell_records[mesh.first_triangle + tl];
    if (shell.h_plus == 0 && shell.h_minus == 0 && shell.side_offset == 0) continue;
    const gpu::Triangle& tri = s.triangles[mesh.first_triangle + tl];
    const gpu::Prism pr = gpu::shell_prism_make(
        vec3(s.vertex_positions[f + tri.v0]), vec3(s.vertex_positions[f + tri.v1]), vec3(s.vertex_positions[f + tri.v2]),
        vec3(s.vertex_normals[f + tri.v0]), vec3(s.vertex_normals[f + tri.v1]), vec3(s.vertex_normals[f + tri.v2]),
        gpu::ShellOffsets{shell.h_plus, shell.h_minus, shell.side_offset});
    vec3 lo = pr.v[0], hi = pr.v[0];
    for (int k = 1; k < 6; ++k) lo = glm::min(lo, pr.v[k]), hi = glm::max(hi, pr.v[k]);
    prisms.push_back(outward_box(lo, hi));
    prism_triangles.push_back(tl);
  }
}

}  // namespace nano::levels
