#include "runtime/placement/copy_enumerator.hpp"

#include "runtime/placement/medium_rule.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "common/error.hpp"
#include "common/singular_value.hpp"
#include "format/checked_math.hpp"
#include "format/package_view.hpp"
#include "shared/ownership.h"
#include "shared/effects.h"
#include "shared/render_membrane_filter.h"
#include "shared/seam.h"
#include "shared/tile_mapper.h"

namespace nano::placement {
namespace {

using format::SectionKind;
using glm::dmat3;
using glm::dvec3;
using glm::ivec2;
using glm::ivec3;
using glm::vec2;
using glm::vec3;

std::string str(std::uint64_t v) { return std::to_string(v); }

// Å by which culling keeps copies near a clip plane that the caller judges atom by atom: verify
// moves the planes by 0.01 Å to tell rounding ties from errors, and must see those atoms.
constexpr double kClipCullSlack = 0.1;

struct Aabb {
  dvec3 lo{std::numeric_limits<double>::infinity()};
  dvec3 hi{-std::numeric_limits<double>::infinity()};
  void add(const dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void add(const Aabb& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
  Aabb grown(double r) const { return {lo - r, hi + r}; }
  static Aabb around(const dvec3& centre, double r) { return {centre - r, centre + r}; }
  // True iff one half-space (n, d) — keep n·p + d ≥ 0 — removes every point of the box.
  bool clipped_by_any(const std::vector<glm::dvec4>& half_spaces) const {
    for (const glm::dvec4& h : half_spaces) {
      const dvec3 n(h);
      const dvec3 best(n.x > 0 ? hi.x : lo.x, n.y > 0 ? hi.y : lo.y, n.z > 0 ? hi.z : lo.z);
      if (glm::dot(n, best) + h.w < 0) return true;
    }
    return false;
  }
  bool meets(const Aabb& b) const {
    return lo.x <= b.hi.x && lo.y <= b.hi.y && lo.z <= b.hi.z && b.lo.x <= hi.x && b.lo.y <= hi.y && b.lo.z <= hi.z;
  }
};

}  // namespace

bool WorldBox::meets_sphere(const dvec3& centre, double radius) const {
  const dvec3 nearest = glm::clamp(centre, min, max);
  const dvec3 d = centre - nearest;
  return glm::dot(d, d) <= radius * radius;
}

// What the walk needs about one compartment, derived and checked once.
struct CompartmentPlan {
  bool membrane = false;
  bool core = false;
  float s = 0, s_over_S = 0;        // tile UV size and UV units per Å (docs/placement.md)
  float smooth = 0;                  // shape factor of the membrane's surface (Compartment.scales.w)
  std::uint32_t membrane_slots = 0;  // W·H
  std::uint32_t square_instances = 0, cube_instances = 0;  // I₂, I₃: the largest tile / cube
  std::uint64_t membrane_span = 0, core_span = 0;          // copy numbers of one instance
  double membrane_reach = 0;  // |z| + molecule radius, over every square's molecules
  Aabb cube_reach;            // cube-space bounds of every cube's molecule spheres
  Aabb bound;                 // compartment space: everything any copy can reach
  double tolerance = 0;       // slack for float rounding of the placement, Å
  // Per local triangle, where the copies it owns can reach (walk_membrane says how): computed once,
  // so a small query culls a triangle by one box test instead of building its chart.
  std::vector<Aabb> triangle_reach;
  glm::dvec2 square_lo{0.0}, square_hi{0.0};  // tile-space xy bounds of every square's molecules, Å
};

struct InstancePlan {
  dmat3 linear{1.0}, inverse{1.0};
  dvec3 translation{0.0};
  double stretch = 1;
  std::uint64_t base = 0;
};

struct CopyEnumerator::Impl : format::PackageView {
  const format::Package& p;

  std::vector<double> type_radius;  // from the atoms, not MoleculeType.aabb_min.w
  std::vector<CompartmentPlan> plans;
  std::vector<InstancePlan> instance_plans;
  std::uint64_t number_limit = 0;

  CopyOptions options;

  // The medium: per instance its region → compartment record and the region-space box of its field.
  std::vector<gpu::MediumInstance> medium_records;
  std::vector<std::pair<dvec3, dvec3>> exclusion_boxes;
  bool medium_on = false;  // a medium, and shown
  std::uint64_t medium_base = 0;
  std::uint32_t medium_instances_per_cube = 0;
  Aabb medium_reach;  // cube-space bounds of every medium molecule's sphere

  Impl(const format::Package& package, const CopyOptions& o)
      : PackageView(package), p(package), type_radius(atom_bounding_radii()), options(o) {
    if (options.instance_transforms.empty())
      for (const gpu::CompartmentInstance& ci : compartment_instances) options.instance_transforms.push_back(format::instance_transform(ci));
    if (options.instance_transforms.size() != compartment_instances.size())
      fail("compartment_instances", std::to_string(options.instance_transforms.size()) + " transforms given for " +
                                        std::to_string(compartment_instances.size()) + " instances");
    for (std::uint32_t c = 0; c < compartments.size(); ++c) plans.push_back(plan(c));
    for (std::uint32_t i = 0; i < compartment_instances.size(); ++i) instance_plans.push_back(plan_instance(i));
    medium_on = !medium.empty() && options.medium;
    if (medium_on) plan_medium();
  }

  void plan_medium() {
    const gpu::Medium& m = medium[0];
    medium_records = medium_instances(*this, options.instance_transforms);
    for (std::uint32_t i = 0; i < compartment_instances.size(); ++i)
      exclusion_boxes.push_back(exclusion_box(exclusion_fields[compartment_instances[i].compartment], options.instance_transforms[i],
                                              dvec3(m.region_min)));
    medium_instances_per_cube = m.tiles.z;
    for (std::uint32_t t = m.tiles.x; t < m.tiles.x + m.tiles.y; ++t)
      for (std::uint32_t k = tiles3d[t].first_instance; k < tiles3d[t].first_instance + tiles3d[t].instance_count; ++k)
        medium_reach.add(Aabb{dvec3(instances[k].position) - type_radius[instances[k].molecule_type], dvec3(instances[k].position) + type_radius[instances[k].molecule_type]});
    medium_base = number_limit;
    const auto boxes = format::checked_mul(std::uint64_t{m.boxes.x} * m.boxes.y, m.boxes.z);
    const auto span = boxes ? format::checked_mul(*boxes, medium_instances_per_cube) : std::nullopt;
    const auto end = span ? format::checked_add(number_limit, *span) : std::nullopt;
    if (!end) fail("medium", "copy numbers exceed 64 bits");
    number_limit = *end;
  }

  // The instances whose exclusion box meets medium box ijk's reach (its middle and every copy centre
  // of its cube, with a margin far above their float rounding): the only ones near_instances can
  // find for that box, so a blood scene's copies each test a few instances rather than all of them.
  std::vector<std::uint32_t> instances_meeting_box(const ivec3& ijk, double B) const {
    const dvec3 corner = dvec3(ijk) * B;
    const dvec3 lo = corner + glm::min(medium_reach.lo, dvec3(0.0)) - 1.0;
    const dvec3 hi = corner + glm::max(medium_reach.hi, dvec3(B)) + 1.0;
    std::vector<std::uint32_t> meeting;
    for (std::uint32_t i = 0; i < exclusion_boxes.size(); ++i) {
      const auto& [box_lo, box_hi] = exclusion_boxes[i];
      if (glm::all(glm::lessThanEqual(box_lo, hi)) && glm::all(glm::lessThanEqual(lo, box_hi))) meeting.push_back(i);
    }
    return meeting;
  }

  // Of `candidates`, the instances whose exclusion box holds region-space point c.
  void near_instances(const vec3& c, const std::vector<std::uint32_t>& candidates, std::vector<std::uint32_t>& near) const {
    near.clear();
    const dvec3 q(c);
    for (const std::uint32_t i : candidates) {
      const auto& [lo, hi] = exclusion_boxes[i];
      if (q.x >= lo.x && q.y >= lo.y && q.z >= lo.z && q.x <= hi.x && q.y <= hi.y && q.z <= hi.z) near.push_back(i);
    }
  }

  void walk_medium_box(const ivec3& ijk, const WorldBox& cull, const std::function<void(const Copy&)>& visit,
                       const CopyEnumerator::SphereTest& may_meet = {}) const {
    const gpu::Medium& m = medium[0];
    if (glm::any(glm::lessThan(ijk, ivec3(0))) || glm::any(glm::greaterThanEqual(ijk, ivec3(glm::uvec3(m.boxes))))) return;
    const float B = m.region_min.w;
    // The medium's copies stand in region space: an identity instance at the box's world corner.
    InstancePlan ip;
    ip.translation = dvec3(m.region_min) + dvec3(ijk) * double(B);
    Emitter emit{*this, ip, cull, visit, {}, {}};
    emit.copy.id.compartment_instance = gpu::NANO_MEDIUM_OWNER;
    emit.copy.id.kind = CopyKind::medium;
    const std::uint32_t box = std::uint32_t(ijk.x) + m.boxes.x * (std::uint32_t(ijk.y) + m.boxes.y * std::uint32_t(ijk.z));
    emit.copy.id.element = box;
    emit.copy.id.cell = ijk;
    // A box wholly inside an instance keeps nothing: trilinear values change by at most √3 per unit
    // step, so a centre value below margin − 1.5·B rejects every copy of the box.
    const std::vector<std::uint32_t> candidates = instances_meeting_box(ijk, double(B));
    std::vector<std::uint32_t> near;
    const vec3 middle = gpu::medium_copy_centre(ijk, B, vec3(B / 2));
    near_instances(middle, candidates, near);
    for (const std::uint32_t i : near)
      if (double(exclusion_value(*this, medium_records[i], middle)) <
          double(exclusion_fields[medium_records[i].ids.x].limits.x) - 1.5 * double(B))
        return;
    const gpu::Tile3D& cube = tiles3d[recipe_cell(m.boxes.w, ijk.x, ijk.y, ijk.z)];
    for (std::uint32_t k = 0; k < cube.instance_count; ++k) {
      const gpu::MoleculeInstance& inst = instances[cube.first_instance + k];
      if (options.visibility.molecule_type_hidden(inst.molecule_type)) continue;  // before its keep test, the costly part
      // The sphere the Emitter gives the copy (jitter turns a copy about its origin, never moves it).
      const dvec3 origin = dvec3(gpu::core_soluble_molecule(vec3(0.0f), vec3(inst.position), inst.rotation).translation) + ip.translation;
      const double radius = type_radius[inst.molecule_type] * ip.stretch;
      if (!cull.meets_sphere(origin, radius) || (may_meet && !may_meet(origin, radius))) continue;
      const vec3 c = gpu::medium_copy_centre(ijk, B, vec3(inst.position));
      near_instances(c, candidates, near);
      if (!medium_copy_kept(*this, medium_records, near, c, molecules[inst.molecule_type].aabb_min.w)) continue;
      emit.copy.id.instance = k;
      emit.copy.number = medium_base + std::uint64_t{box} * medium_instances_per_cube + k;
      emit(gpu::core_soluble_molecule(vec3(0.0f), vec3(inst.position), inst.rotation), inst.molecule_type);
    }
  }

  [[noreturn]] void fail(const std::string& where, const std::string& rule) const { throw InputError(p.name(), where, rule); }

  vec3 vertex(std::uint32_t mesh_first, std::uint32_t v) const { return vec3(vertex_positions[mesh_first + v]); }

  CompartmentPlan plan(std::uint32_t ci) const {
    const gpu::Compartment& c = compartments[ci];
    const std::string where = "compartments[" + str(ci) + "]";
    CompartmentPlan plan;
    plan.membrane = c.membrane_recipe != gpu::NANO_NO_INDEX;
    plan.core = c.soluble_recipe != gpu::NANO_NO_INDEX;
    const gpu::Mesh& mesh = meshes[c.mesh];
    double magnitude = 1;
    if (plan.membrane) {
      const float S = c.scales.y;
      plan.s = S / c.scales.x;
      plan.s_over_S = plan.s / S;
      plan.smooth = c.scales.w;
      for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t) {
        const gpu::Tile2D& tile = tiles2d[t];
        if (tile.size.x != S || tile.size.y != S)
          fail(where, "Wang square " + str(t) + " is not " + std::to_string(S) + " Å wide like the compartment (scales.y)");
        plan.square_instances = std::max(plan.square_instances, tile.instance_count);
        for (std::uint32_t m = tile.first_instance; m < tile.first_instance + tile.instance_count; ++m) {
          plan.membrane_reach = std::max(plan.membrane_reach,
                                         std::abs(double(instances[m].position.z)) + type_radius[instances[m].molecule_type]);
          plan.square_lo = glm::min(plan.square_lo, glm::dvec2(instances[m].position));
          plan.square_hi = glm::max(plan.square_hi, glm::dvec2(instances[m].position));
        }
      }

      check_chart(ci, plan);
      Aabb mesh_box;
      for (std::uint32_t v = 0; v < mesh.vertex_count; ++v) mesh_box.add(dvec3(vertex(mesh.first_vertex, v)));
      if (mesh.vertex_count > 0) {
        magnitude = std::max({magnitude, glm::length(mesh_box.lo), glm::length(mesh_box.hi)});
        double bulge = 0;  // how far the smooth surface leaves the facets (chart_smooth_bulge)
        for (std::uint32_t tl = 0; plan.smooth > 0 && tl < mesh.triangle_count; ++tl) {
          const double b = gpu::chart_smooth_bulge(make_chart(mesh, triangles[mesh.first_triangle + tl]), plan.smooth);
          if (std::isfinite(b)) bulge = std::max(bulge, b);
        }
        plan.bound.add(mesh_box.grown(plan.membrane_reach + bulge));
      }
      const auto slots = format::checked_mul(c.replication_width, c.replication_height);
      if (*slots > 0xFFFFFFFFu) fail(where, "replication area exceeds 2^32 tiles");
      plan.membrane_slots = std::uint32_t(*slots);
      const auto cells = format::checked_mul(mesh.triangle_count, plan.membrane_slots);
      const auto span = cells ? format::checked_mul(*cells, plan.square_instances) : std::nullopt;
      if (!span) fail(where, "membrane copy numbers exceed 64 bits");
      plan.membrane_span = *span;
    }
    if (plan.core) {
      const float B = c.grid_min.w;
      for (std::uint32_t t = c.soluble_first_tile; t < c.soluble_first_tile + c.soluble_tile_count; ++t) {
        const gpu::Tile3D& cube = tiles3d[t];
        if (c.scales.z != B || cube.size.x != B || cube.size.y != B || cube.size.z != B)
          fail(where, "Wang cube " + str(t) + " and scales.z must both equal the box edge " + std::to_string(B) + " Å");
        plan.cube_instances = std::max(plan.cube_instances, cube.instance_count);
        for (std::uint32_t m = cube.first_instance; m < cube.first_instance + cube.instance_count; ++m) {
          const double r = type_radius[instances[m].molecule_type];
          plan.cube_reach.add(dvec3(instances[m].position) - r);
          plan.cube_reach.add(dvec3(instances[m].position) + r);
        }
      }
      if (plan.cube_instances > 0) {
        const dvec3 grid_min(c.grid_min);
        const dvec3 last_box = grid_min + double(B) * (dvec3(glm::uvec3(c.grid_dims)) - 1.0);
        plan.bound.add(Aabb{grid_min + plan.cube_reach.lo, last_box + plan.cube_reach.hi});
        magnitude = std::max({magnitude, glm::length(grid_min), glm::length(last_box + double(B))});
      }
      const std::uint64_t boxes = std::uint64_t{c.grid_dims.x} * c.grid_dims.y * c.grid_dims.z;  // fits (validator)
      const auto span = format::checked_mul(boxes, plan.cube_instances);
      if (!span) fail(where, "core copy numbers exceed 64 bits");
      plan.core_span = *span;
    }
    // The float placement differs from exact arithmetic by a few ulps of the coordinates involved;
    // culling only needs to stay conservative, so the slack is generous.
    plan.tolerance = 1e-3 * magnitude;
    plan.bound = plan.bound.grown(plan.tolerance);
    if (plan.membrane) plan.triangle_reach = triangle_reaches(mesh, plan);
    return plan;
  }

  // A copy a triangle owns sits over the triangle (its uv_m lies in the UV triangle), lifted off it
  // by the smooth surface's bulge and at most |z| along the unit normal, its atoms within the type
  // radius: the triangle's AABB grown by that (and the tolerance).
  std::vector<Aabb> triangle_reaches(const gpu::Mesh& mesh, const CompartmentPlan& plan) const {
    std::vector<Aabb> reaches(mesh.triangle_count);
    for (std::uint32_t tl = 0; tl < mesh.triangle_count; ++tl) {
      const gpu::Triangle& tri = triangles[mesh.first_triangle + tl];
      double lift = plan.smooth > 0 ? double(gpu::chart_smooth_bulge(make_chart(mesh, tri), plan.smooth)) : 0.0;
      if (!std::isfinite(lift)) lift = 0.0;  // a degenerate triangle: owns nothing
      Aabb reach;
      for (std::uint32_t v : {tri.v0, tri.v1, tri.v2}) reach.add(dvec3(vertex(mesh.first_vertex, v)));
      reaches[tl] = reach.grown(plan.membrane_reach + lift + plan.tolerance);
    }
    return reaches;
  }

  // Rules of docs/placement.md the validator leaves to placement: UVs on the 2^-24 grid with
  // |uv| < 16, a usable chart wherever the UV triangle owns anything, and every triangle's
  // replication area within W × H.
  void check_chart(std::uint32_t ci, const CompartmentPlan& plan) const {
    const gpu::Compartment& c = compartments[ci];
    const gpu::Mesh& mesh = meshes[c.mesh];
    for (std::uint32_t v = mesh.first_vertex; v < mesh.first_vertex + mesh.vertex_count; ++v)
      for (int a = 0; a < 2; ++a) {
        const double q = double(vertex_uvs[v][a]) * gpu::kOwnQuantScale;
        if (!(std::abs(vertex_uvs[v][a]) < 16.0f) || q != std::floor(q))
          fail("vertex_uvs[" + str(v) + "]",
               "UV " + std::to_string(vertex_uvs[v][a]) + " of compartment " + str(ci) +
                   "'s mesh is not a multiple of 2^-24 below 16 in magnitude (docs/placement.md rule 1)");
      }
    for (std::uint32_t t = mesh.first_triangle; t < mesh.first_triangle + mesh.triangle_count; ++t) {
      const gpu::Triangle& tri = triangles[t];
      const vec2 t0 = vertex_uvs[mesh.first_vertex + tri.v0], t1 = vertex_uvs[mesh.first_vertex + tri.v1], t2 = vertex_uvs[mesh.first_vertex + tri.v2];
      if (gpu::own_edge_inner_q(gpu::own_quantize(t0), gpu::own_quantize(t1), gpu::own_quantize(t2)) == 0) continue;
      const gpu::TriangleChart chart = make_chart(mesh, tri);
      if (!gpu::chart_valid(chart))
        fail("triangles[" + str(t) + "]", "the UV triangle owns molecules but the triangle is degenerate in space");
      const ivec2 extent = gpu::replication_extent(glm::min(t0, glm::min(t1, t2)), glm::max(t0, glm::max(t1, t2)), plan.s);
      if (extent.x > int(c.replication_width) || extent.y > int(c.replication_height))
        fail("triangles[" + str(t) + "]", "needs a replication area of " + std::to_string(extent.x) + "×" +
                                              std::to_string(extent.y) + " tiles, more than compartment " + str(ci) + "'s " +
                                              str(c.replication_width) + "×" + str(c.replication_height));
    }
  }

  gpu::TriangleChart make_chart(const gpu::Mesh& mesh, const gpu::Triangle& tri) const {
    const std::uint32_t f = mesh.first_vertex;
    return gpu::chart_make(vertex(f, tri.v0), vertex(f, tri.v1), vertex(f, tri.v2), vertex_uvs[f + tri.v0], vertex_uvs[f + tri.v1],
                           vertex_uvs[f + tri.v2], vec3(vertex_normals[f + tri.v0]), vec3(vertex_normals[f + tri.v1]), vec3(vertex_normals[f + tri.v2]));
  }

  InstancePlan plan_instance(std::uint32_t i) {
    const gpu::CompartmentInstance& ci = compartment_instances[i];
    InstancePlan ip;
    const format::InstanceTransform& t = options.instance_transforms[i];
    ip.linear = t.linear;
    ip.translation = t.translation;
    const double det = glm::determinant(ip.linear);
    if (!(std::abs(det) > 1e-12)) fail("compartment_instances[" + str(i) + "]", "transform is singular");
    ip.inverse = glm::inverse(ip.linear);
    ip.stretch = largest_singular_value(ip.linear);
    ip.base = number_limit;
    const CompartmentPlan& plan = plans[ci.compartment];
    const auto end = format::checked_add(number_limit, plan.membrane_span);
    const auto end2 = end ? format::checked_add(*end, plan.core_span) : std::nullopt;
    if (!end2) fail("compartment_instances[" + str(i) + "]", "copy numbers exceed 64 bits");
    number_limit = *end2;
    return ip;
  }

  // The compartment-space AABB of the preimage of the world box under an instance.
  Aabb local_query(const InstancePlan& ip, const WorldBox& box) const {
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(box.min[a]) || !std::isfinite(box.max[a]))  // corners at infinity have no preimage
        return {dvec3(-std::numeric_limits<double>::infinity()), dvec3(std::numeric_limits<double>::infinity())};
    Aabb q;
    for (int corner = 0; corner < 8; ++corner) {
      const dvec3 w((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                    (corner & 4) ? box.max.z : box.min.z);
      q.add(ip.inverse * (w - ip.translation));
    }
    return q;
  }

  // Turns a float compartment-space placement into a world copy and hands it on if it can reach the box.
  struct Emitter {
    const Impl& scene;
    const InstancePlan& ip;
    const WorldBox& box;
    const std::function<void(const Copy&)>& visit;
    Copy copy;
    std::vector<glm::dvec4> local_clip;  // the clip half-spaces in the instance's compartment space

    void operator()(gpu::Affine3 placement, std::uint32_t type) {
      if (scene.options.visibility.molecule_type_hidden(type)) return;
      if (scene.options.jitter) {
        const glm::vec3& j = scene.options.jitter_parameters;
        const glm::uvec2 number(std::uint32_t(copy.number), std::uint32_t(copy.number >> 32));
        placement = gpu::jitter_placement(placement, gpu::jitter_rotation(number, j.x, j.y, j.z));
      }
      copy.molecule_type = type;
      copy.linear = ip.linear * dmat3(placement.linear);
      copy.origin = ip.linear * dvec3(placement.translation) + ip.translation;
      copy.stretch = ip.stretch;
      copy.radius = scene.type_radius[type] * ip.stretch;
      for (const glm::dvec4& h : scene.options.clip)  // every atom centre of the copy clipped
        if (glm::dot(dvec3(h), copy.origin) + h.w + kClipCullSlack < -copy.radius) return;
      if (box.meets_sphere(copy.origin, copy.radius)) visit(copy);
    }
  };

  // Triangles [first, first + count) of the mesh (local indices; clamped to the mesh).
  void walk_membrane(const CompartmentPlan& plan, const gpu::Compartment& c, const Aabb& query, Emitter& emit,
                     std::uint32_t first = 0, std::uint32_t count = ~0u) const {
    const gpu::Mesh& mesh = meshes[c.mesh];
    const std::uint32_t end = first + std::min(count, mesh.triangle_count - std::min(first, mesh.triangle_count));
    for (std::uint32_t tl = first; tl < end; ++tl) {
      const std::uint32_t t = mesh.first_triangle + tl;
      const gpu::Triangle& tri = triangles[t];
      const std::uint32_t f = mesh.first_vertex;
      const Aabb& reach = plan.triangle_reach[tl];
      if (!reach.meets(query) || reach.clipped_by_any(emit.local_clip)) continue;
      const gpu::TriangleChart chart = make_chart(mesh, tri);
      double lift = plan.smooth > 0 ? double(gpu::chart_smooth_bulge(chart, plan.smooth)) : 0.0;
      if (!std::isfinite(lift)) lift = 0.0;
      const double grow = plan.membrane_reach + lift + plan.tolerance;
      const vec2 t0 = vertex_uvs[f + tri.v0], t1 = vertex_uvs[f + tri.v1], t2 = vertex_uvs[f + tri.v2];
      if (gpu::own_edge_inner_q(gpu::own_quantize(t0), gpu::own_quantize(t1), gpu::own_quantize(t2)) == 0) continue;
      const vec2 uv_min = glm::min(t0, glm::min(t1, t2)), uv_max = glm::max(t0, glm::max(t1, t2));
      const ivec2 origin = gpu::replication_origin(uv_min, plan.s);
      const ivec2 extent = gpu::replication_extent(uv_min, uv_max, plan.s);
      // The seam rule (shared/seam.h, docs/placement.md step 4): this triangle's yielding seam edges.
      // A package without triangle_shells (the section is optional; the validator makes it parallel
      // to triangles when present) has no seam bits.
      const std::uint32_t seam_edges = triangle_shells.empty() ? 0u : triangle_shells[t].seam_edges;
      const vec3 p0 = vertex(f, tri.v0), p1 = vertex(f, tri.v1), p2 = vertex(f, tri.v2);
      emit.copy.id.kind = CopyKind::membrane;
      emit.copy.id.element = t;
      for (int sy = 0; sy < extent.y; ++sy)
        for (int sx = 0; sx < extent.x; ++sx) {
          const ivec2 cell = gpu::replication_tile_index(origin, ivec2(sx, sy));
          const std::uint64_t slot = std::uint64_t(sx) + std::uint64_t(c.replication_width) * sy;
          const gpu::Tile2D& tile = tiles2d[recipe_cell(c.membrane_recipe, cell.x, cell.y, 0)];
          const vec2 g = gpu::replication_tile_uv(cell, plan.s);
          // Where this cell's copies can stand: its molecules' UV box through the facet's affine
          // chart (a copy sits over its flat point, lifted by at most the bulge and |z|), so a small
          // query places the copies of the cells it meets, not of the whole triangle.
          Aabb cell_reach;
          for (int k = 0; k < 4; ++k) {
            const glm::dvec2 xy((k & 1) ? plan.square_hi.x : plan.square_lo.x, (k & 2) ? plan.square_hi.y : plan.square_lo.y);
            cell_reach.add(dvec3(gpu::chart_position(chart, g + vec2(xy) * plan.s_over_S)));
          }
          cell_reach = cell_reach.grown(grow);
          if (!cell_reach.meets(query) || cell_reach.clipped_by_any(emit.local_clip)) continue;
          emit.copy.id.cell = ivec3(cell, 0);
          for (std::uint32_t m = 0; m < tile.instance_count; ++m) {
            const gpu::MoleculeInstance& inst = instances[tile.first_instance + m];
            // Ownership and reach first, from the molecule's chart point alone (the same uv_m that
            // chart_membrane_molecule computes): most copies of a cell belong to a neighbouring
            // triangle or stand outside a small query, and need no frame.
            vec2 uv_m = gpu::chart_molecule_uv(g, plan.s_over_S, vec3(inst.position));
            if (!gpu::own_triangle_owns(t0, t1, t2, uv_m)) continue;
            const Aabb copy_reach = Aabb::around(dvec3(gpu::chart_position(chart, uv_m)), grow);
            if (!copy_reach.meets(query) || copy_reach.clipped_by_any(emit.local_clip)) continue;
            const gpu::Affine3 placement =
                gpu::chart_membrane_molecule(chart, g, plan.s_over_S, plan.smooth, vec3(inst.position), inst.rotation, uv_m);
            if (gpu::seam_drops(seam_edges, p0, p1, p2, gpu::chart_position(chart, uv_m),
                                molecules[inst.molecule_type].aabb_min.w))
              continue;
            if (!gpu::membrane_copy_listed_shows(membrane_copy_listed(t, gpu::membrane_copy_key(std::uint32_t(slot), m)),
                                                 inst.flags))
              continue;
            emit.copy.id.instance = m;
            emit.copy.number = emit.ip.base + (std::uint64_t{tl} * plan.membrane_slots + slot) * plan.square_instances + m;
            emit(placement, inst.molecule_type);
          }
        }
    }
  }

  // The copies of instance i in `box`: all, or (`triangle`) the membrane copies of that local triangle.
  void walk_instance(std::uint32_t i, const WorldBox& box, const std::function<void(const Copy&)>& visit,
                     std::optional<std::uint32_t> triangle) const {
    if (i >= compartment_instances.size()) throw std::out_of_range("CopyEnumerator: no compartment instance " + str(i));
    const std::uint32_t ci = compartment_instances[i].compartment;
    if (options.visibility.compartment_hidden(ci)) return;
    const CompartmentPlan& plan = plans[ci];
    const InstancePlan& ip = instance_plans[i];
    const Aabb query = local_query(ip, box);
    if (!plan.bound.meets(query)) return;
    Emitter emit{*this, ip, box, visit, {}, {}};
    emit.copy.id.compartment_instance = i;
    // n·(L c + T) + d = (Lᵀn)·c + (n·T + d): the world half-spaces in compartment space.
    for (const glm::dvec4& h : options.clip)
      emit.local_clip.push_back(
          glm::dvec4(glm::transpose(ip.linear) * dvec3(h), glm::dot(dvec3(h), ip.translation) + h.w + kClipCullSlack));
    if (plan.membrane) {
      if (triangle) walk_membrane(plan, compartments[ci], query, emit, *triangle, 1);
      else walk_membrane(plan, compartments[ci], query, emit);
    }
    if (plan.core && !triangle) walk_core(plan, compartments[ci], query, emit);
  }

  // The keep-mask words of a BOUNDARY box: binary search over the compartment's sorted records.
  const std::uint32_t* keep_mask(const gpu::Compartment& c, std::uint32_t box) const {
    const auto records = boundary_boxes.subspan(c.core_masks.x, c.core_masks.y);
    const auto it = std::lower_bound(records.begin(), records.end(), box,
                                     [](const gpu::BoundaryBox& r, std::uint32_t b) { return r.box < b; });
    if (it == records.end() || it->box != box)  // the validator lists every BOUNDARY box
      fail("boundary_boxes", "BOUNDARY box " + str(box) + " has no keep-mask record");
    return mask_words.data() + it->first_word;
  }

  void walk_core(const CompartmentPlan& plan, const gpu::Compartment& c, const Aabb& query, Emitter& emit) const {
    const double B = c.grid_min.w;
    const dvec3 grid_min(c.grid_min);
    const glm::uvec3 dims(c.grid_dims);
    // Boxes whose copies (box_min + cube_reach) can meet the query, plus one box of slack per side
    // against rounding; the per-copy sphere test decides.
    ivec3 first, last;
    for (int a = 0; a < 3; ++a) {
      const double lo = std::floor((query.lo[a] - grid_min[a] - plan.cube_reach.hi[a]) / B) - 1;
      const double hi = std::floor((query.hi[a] - grid_min[a] - plan.cube_reach.lo[a]) / B) + 1;
      first[a] = int(std::clamp(lo, 0.0, double(dims[a] - 1)));
      last[a] = int(std::clamp(hi, 0.0, double(dims[a] - 1)));
      if (lo > double(dims[a] - 1) || hi < 0) return;
    }
    emit.copy.id.kind = CopyKind::core;
    const std::uint64_t core_base = emit.ip.base + plan.membrane_span;
    // Where the boxes [lo, hi] (inclusive) let their copies reach; clipped slabs and rows are skipped
    // whole, so a view behind a clip plane does not visit every box it removes.
    const auto reach_of = [&](ivec3 lo, ivec3 hi) {
      return Aabb{grid_min + dvec3(lo) * B + plan.cube_reach.lo, grid_min + dvec3(hi) * B + plan.cube_reach.hi}.grown(plan.tolerance);
    };
    const bool clipping = !emit.local_clip.empty();
    for (int k = first.z; k <= last.z; ++k) {
      if (clipping && reach_of(ivec3(first.x, first.y, k), ivec3(last.x, last.y, k)).clipped_by_any(emit.local_clip)) continue;
      for (int j = first.y; j <= last.y; ++j) {
        if (clipping && reach_of(ivec3(first.x, j, k), ivec3(last.x, j, k)).clipped_by_any(emit.local_clip)) continue;
        for (int i = first.x; i <= last.x; ++i) {
          const std::uint32_t box = std::uint32_t(i) + dims.x * (std::uint32_t(j) + dims.y * std::uint32_t(k));
          const std::uint8_t occ = occupancy[c.grid_dims.w + box];
          if (occ == gpu::NANO_BOX_OUTSIDE) continue;
          const std::uint32_t* mask = occ == gpu::NANO_BOX_BOUNDARY ? keep_mask(c, box) : nullptr;
          const gpu::Tile3D& cube = tiles3d[recipe_cell(c.soluble_recipe, i, j, k)];
          const vec3 box_min = gpu::core_box_min(vec3(c.grid_min), vec3(c.grid_min.w), ivec3(i, j, k));
          if (clipping && reach_of(ivec3(i, j, k), ivec3(i, j, k)).clipped_by_any(emit.local_clip)) continue;
          emit.copy.id.element = box;
          emit.copy.id.cell = ivec3(i, j, k);
          for (std::uint32_t m = 0; m < cube.instance_count; ++m) {
            const gpu::MoleculeInstance& inst = instances[cube.first_instance + m];
            if (mask && !((mask[m / 32] >> (m % 32)) & 1u)) continue;
            emit.copy.id.instance = m;
            emit.copy.number = core_base + std::uint64_t{box} * plan.cube_instances + m;
            emit(gpu::core_soluble_molecule(box_min, vec3(inst.position), inst.rotation), inst.molecule_type);
          }
        }
      }
    }
  }
};

CopyEnumerator::CopyEnumerator(const format::Package& package, const CopyOptions& options)
    : impl_(std::make_unique<Impl>(package, options)) {}
const std::vector<format::InstanceTransform>& CopyEnumerator::instance_transforms() const {
  return impl_->options.instance_transforms;
}
CopyEnumerator::~CopyEnumerator() = default;
CopyEnumerator::CopyEnumerator(CopyEnumerator&&) noexcept = default;

std::uint64_t CopyEnumerator::copy_number_limit() const { return impl_->number_limit; }

bool CopyEnumerator::has_medium() const { return impl_->medium_on; }

void CopyEnumerator::for_each_medium_copy(const glm::ivec3& box, const WorldBox& cull, const std::function<void(const Copy&)>& visit,
                                          const SphereTest& may_meet) const {
  if (impl_->medium_on) impl_->walk_medium_box(box, cull, visit, may_meet);
}

void CopyEnumerator::for_each_medium_copy(const WorldBox& box, const std::function<void(const Copy&)>& visit,
                                          std::uint64_t max_boxes) const {
  if (!impl_->medium_on) return;
  const Impl& s = *impl_;
  const gpu::Medium& m = s.medium[0];
  const double B = m.region_min.w;
  ivec3 first, last;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::floor((box.min[a] - m.region_min[a] - s.medium_reach.hi[a]) / B) - 1;
    const double hi = std::floor((box.max[a] - m.region_min[a] - s.medium_reach.lo[a]) / B) + 1;
    if (lo > double(m.boxes[a]) - 1 || hi < 0) return;
    first[a] = int(std::clamp(lo, 0.0, double(m.boxes[a]) - 1)), last[a] = int(std::clamp(hi, 0.0, double(m.boxes[a]) - 1));
  }
  const double count = double(last.x - first.x + 1) * (last.y - first.y + 1) * (last.z - first.z + 1);
  if (count > double(max_boxes))
    s.fail("medium", "the box holds " + std::to_string(std::uint64_t(count)) + " of the medium's boxes, more than " +
                         std::to_string(max_boxes) + ": choose a smaller box");
  for (int k = first.z; k <= last.z; ++k)
    for (int j = first.y; j <= last.y; ++j)
      for (int i = first.x; i <= last.x; ++i) s.walk_medium_box(ivec3(i, j, k), box, visit);
}

void CopyEnumerator::for_each_copy(const WorldBox& box, const std::function<void(const Copy&)>& visit) const {
  for (std::uint32_t i = 0; i < impl_->compartment_instances.size(); ++i) for_each_copy_of(i, box, visit);
}

void CopyEnumerator::for_each_copy_of(std::uint32_t i, const WorldBox& box, const std::function<void(const Copy&)>& visit) const {
  impl_->walk_instance(i, box, visit, std::nullopt);
}

void CopyEnumerator::for_each_membrane_copy(std::uint32_t i, std::uint32_t triangle,
                                            const std::function<void(const Copy&)>& visit) const {
  impl_->walk_instance(i, WorldBox::everything(), visit, triangle);
}

}  // namespace nano::placement
