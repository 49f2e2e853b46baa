// CGAL's isotropic remeshing and AABB distance queries, in their own translation unit (template-heavy).
#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <stdexcept>
#include <vector>
#include <cstdio>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include "bake/mesh/mesh_remesh.hpp"
#include "bake/mesh/number_text.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr double kSmoothingWeight = 0.5;
constexpr int kMaxSmoothingSteps = 200;
constexpr int kMaxExtraSteps = 40;
constexpr int kHoldRounds = 6;
constexpr double kHoldOvershoot = 1.5;  // pull a little past the excess: neighbours move too
constexpr double kExtraStepGainDegrees = 0.5;  // per two extra steps
constexpr int kRemeshIterations = 3;
// Neighbouring faces of a coarsened region turn by at most about this (rad: 8°, well under the 20°
// the shells follow).
constexpr double kTurnPerEdge = 0.14;
// A coarser level is made only when it would remesh at least this many faces.
constexpr std::size_t kCoarsenAtLeast = 64;
constexpr int kBorderRings = 3;
// A vertex made at under this times a level's edge (three quarters of the level just below) was made
// two or more levels down.
constexpr double kLowerLevelEdge = 0.375;
constexpr int kBorderSmoothingSteps = 8;
// Triangles with an angle under this are remeshed again with their surroundings, a few rounds at most.
constexpr double kSliverMendDegrees = 5.0;
// A cap (one angle near 180°) is flat but short across: the corner normals it interpolates turn over
// its small height, as tight a bend as the judgement sees (a 1 µm cube's corners: 166°, a radius of
// 20 Å against the 31 Å half a bilayer needs). Mended like a sliver.
constexpr double kCapMendDegrees = 150.0;
constexpr int kMendRounds = 3;
// A cap whose neighbour across its longest edge lies in its plane within this is mended by a flip.
constexpr double kFlatCapDegrees = 2.0;

// `source` names the mesh when CGAL finds it is no closed polygon mesh: check-mesh refuses such meshes
// before anyone remeshes them, so only a disagreement between its checks and CGAL's comes here.
SurfaceMesh to_surface_mesh(const ProxyMesh& mesh, const InputSource& source) {
  std::vector<Point> points;
  points.reserve(mesh.positions.size());
  for (const glm::dvec3& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) polygons.push_back({t[0], t[1], t[2]});
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    source.fail("cannot remesh: the faces do not form an oriented 2-manifold");
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  if (!CGAL::is_closed(sm)) source.fail("cannot remesh: the mesh has holes");
  return sm;
}

ProxyMesh to_proxy_mesh(SurfaceMesh& sm) {
  sm.collect_garbage();
  ProxyMesh mesh;
  mesh.positions.reserve(sm.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    const Point& p = sm.point(v);
    mesh.positions.emplace_back(p.x(), p.y(), p.z());
  }
  for (SurfaceMesh::Face_index f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = std::uint32_t(v);
    mesh.triangles.push_back(t);
  }
  compute_angle_weighted_normals(mesh);
  return mesh;
}

// Face normal angle across edge e, degrees (0 on a border).
double crease_degrees(const SurfaceMesh& sm, SurfaceMesh::Edge_index e) {
  if (sm.is_border(e)) return 0.0;
  const SurfaceMesh::Halfedge_index h = sm.halfedge(e);
  const Vector a = PMP::compute_face_normal(sm.face(h), sm);
  const Vector b = PMP::compute_face_normal(sm.face(sm.opposite(h)), sm);
  return std::acos(std::clamp(a * b, -1.0, 1.0)) * kDegreesPerRadian;
}

// Marks every vertex within `rings` edges of one marked already (indexed by vertex). A breadth-first
// walk from the marked ones, ring by ring: its cost follows the zone, not the mesh times the rings
// (a 1 µm CAD part's creases are grown by 20 rings, 100 times).
void grow_by_rings(const SurfaceMesh& sm, std::vector<bool>& marked, int rings) {
  std::vector<SurfaceMesh::Vertex_index> ring, next;
  for (SurfaceMesh::Vertex_index v : sm.vertices())
    if (marked[std::size_t(v)]) ring.push_back(v);
  for (int r = 0; r < rings && !ring.empty(); ++r) {
    next.clear();
    for (SurfaceMesh::Vertex_index v : ring)
      for (SurfaceMesh::Vertex_index u : CGAL::vertices_around_target(sm.halfedge(v), sm))
        if (!marked[std::size_t(u)]) {
          marked[std::size_t(u)] = true;
          next.push_back(u);
        }
    ring.swap(next);
  }
}

// The vertices within `rings` edges of an edge sharper than `degrees`: only they are smoothed,
// so smooth parts of the user's surface (a sphere's cap) do not shrink.
std::vector<bool> near_creases(const SurfaceMesh& sm, double degrees, int rings) {
  std::vector<bool> marked(sm.number_of_vertices(), false);
  for (SurfaceMesh::Edge_index e : sm.edges())
    if (crease_degrees(sm, e) > degrees) marked[std::size_t(sm.vertex(e, 0))] = marked[std::size_t(sm.vertex(e, 1))] = true;
  grow_by_rings(sm, marked, rings);
  return marked;
}

// One umbrella step of the marked vertices: each moves by w·(mean of its neighbours − itself).
void umbrella_step(SurfaceMesh& sm, const std::vector<bool>& marked, double w, std::vector<Point>& scratch) {
  scratch.assign(sm.number_of_vertices(), CGAL::ORIGIN);
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    const Point& p = sm.point(v);
    scratch[std::size_t(v)] = p;
    if (!marked[std::size_t(v)]) continue;
    Vector sum(0, 0, 0);
    int n = 0;
    for (SurfaceMesh::Vertex_index u : CGAL::vertices_around_target(sm.halfedge(v), sm)) {
      sum = sum + (sm.point(u) - CGAL::ORIGIN);
      ++n;
    }
    if (n > 0) scratch[std::size_t(v)] = p + w * (CGAL::ORIGIN + sum / double(n) - p);
  }
  for (SurfaceMesh::Vertex_index v : sm.vertices()) sm.point(v) = scratch[std::size_t(v)];
}

// Vertices are held half an edge inside the bound: a chord or a face between two vertices on a
// rounded crease lies farther from the input than its corners.
double vertex_bound(const RemeshOptions& options) {
  return std::max(options.max_distance - 0.5 * options.edge, 0.5 * options.max_distance);
}

// Every vertex farther than `bound` from the input surface moves back along its offset to `bound`;
// with `moved`, only those marked there (the others stayed where the last hold left them: a closest
// point on a 75k-triangle scan is most of a smoothing step's cost).
void hold_near(SurfaceMesh& sm, const Tree& input, double bound, const std::vector<bool>* moved = nullptr) {
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    if (moved && !(*moved)[std::size_t(v)]) continue;
    const Point p = sm.point(v);
    const Point q = input.closest_point(p);
    const double d = std::sqrt(CGAL::squared_distance(p, q));
    if (d > bound) sm.point(v) = q + (p - q) * (bound / d);
  }
}

double largest_crease(const SurfaceMesh& sm) {
  double largest = 0.0;
  for (SurfaceMesh::Edge_index e : sm.edges()) largest = std::max(largest, crease_degrees(sm, e));
  return largest;
}

// The faces with a corner among `marked` vertices.
std::vector<SurfaceMesh::Face_index> faces_touching(const SurfaceMesh& sm, const std::vector<bool>& marked) {
  std::vector<SurfaceMesh::Face_index> out;
  for (SurfaceMesh::Face_index f : sm.faces())
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm))
      if (marked[std::size_t(v)]) {
        out.push_back(f);
        break;
      }
  return out;
}

// Per vertex, the edge (Å) of the remeshing that last made its surroundings: the coarse levels grow
// each out of the one just below it. A vertex new to a pass reads NaN until the pass is over.
using MadeAt = SurfaceMesh::Property_map<SurfaceMesh::Vertex_index, double>;

MadeAt made_at(SurfaceMesh& sm) {
  return sm.add_property_map<SurfaceMesh::Vertex_index, double>("v:made_at", NAN).first;
}

// Before a pass over `patch` at `edge`: its vertices all of whose faces it holds are made at `edge`
// (CGAL keeps the patch's border, so the others keep what made them).
void mark_patch_interior(SurfaceMesh& sm, const std::vector<SurfaceMesh::Face_index>& patch, double edge) {
  std::vector<bool> in_patch(sm.num_faces(), false);
  for (SurfaceMesh::Face_index f : patch) in_patch[std::size_t(f)] = true;
  MadeAt made = made_at(sm);
  for (SurfaceMesh::Face_index f : patch)
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      bool interior = true;
      for (SurfaceMesh::Face_index g : CGAL::faces_around_target(sm.halfedge(v), sm))
        interior = interior && g != SurfaceMesh::null_face() && in_patch[std::size_t(g)];
      if (interior) made[v] = edge;
    }
}

// After it: the vertices it made (NaN, or a slot of a removed interior one) are made at `edge`.
void mark_new_vertices(SurfaceMesh& sm, double edge) {
  MadeAt made = made_at(sm);
  for (SurfaceMesh::Vertex_index v : sm.vertices())
    if (std::isnan(made[v])) made[v] = edge;
}

// CGAL's relaxation divides by the areas it meets: a patch the smoothing crushed flat (a tube thinner
// than the bilayer) is left as it is, for the judgement to name.
bool has_degenerate_face(const SurfaceMesh& sm, const std::vector<SurfaceMesh::Face_index>& patch) {
  return std::any_of(patch.begin(), patch.end(), [&](SurfaceMesh::Face_index f) { return PMP::is_degenerate_triangle_face(f, sm); });
}

// Remeshing passes over `patch` (they project onto the surface they are given, the smoothed one),
// then the vertices held near the input again. The patch's border edges are kept where they run
// (CGAL treats them as constraints), so the rest of the surface is left as it is. False, and the
// patch left as it is, where it holds a degenerate face.
// Where `held`, the vertices the pass leaves where they were are already held, and are not looked
// at again.
bool even_triangles(SurfaceMesh& sm, const std::vector<SurfaceMesh::Face_index>& patch, double edge, const Tree& input,
                    const RemeshOptions& options, int iterations = 1, bool held = true) {
  if (has_degenerate_face(sm, patch)) return false;
  // One per slot, removed ones included (num_vertices), indexed as the vertices are; NaN never equals.
  std::vector<Point> before;
  if (held) {
    before.assign(sm.num_vertices(), Point(NAN, NAN, NAN));
    for (SurfaceMesh::Vertex_index v : sm.vertices()) before[std::size_t(v)] = sm.point(v);
  }
  mark_patch_interior(sm, patch, edge);
  try {
    PMP::isotropic_remeshing(patch, edge, sm, CGAL::parameters::number_of_iterations(iterations));
  } catch (const std::out_of_range&) {
    // CGAL 5.5's collapse check can look up a face's patch in a map that lacks it ("map::at": CGAL's
    // genus-3 sample at 10,000 Å, once per remeshing). It throws before that collapse, so the mesh is
    // whole and the pass only cut short: every vertex is held again below, and the judgement checks
    // the surface as always.
    held = false;
  }
  // Before the garbage goes, a vertex the pass kept has its index still; a slot it reused for a new
  // vertex holds another point (at the very same point it would be held already).
  std::vector<bool> moved(sm.num_vertices(), true);
  for (std::size_t i = 0; held && i < std::min(before.size(), moved.size()); ++i)
    moved[i] = !(sm.point(SurfaceMesh::Vertex_index(SurfaceMesh::size_type(i))) == before[i]);
  hold_near(sm, input, vertex_bound(options), &moved);
  mark_new_vertices(sm, edge);
  sm.collect_garbage();
  return true;
}

// How fast the surface turns at each vertex (rad per Å): the largest angle between its normal and a
// neighbour's over their distance, then the largest over its one-ring, so that a region's size is
// set by its most curved corner.
std::vector<double> vertex_turn_rates(const SurfaceMesh& sm) {
  std::vector<Vector> normal(sm.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : sm.vertices()) normal[std::size_t(v)] = PMP::compute_vertex_normal(v, sm);
  std::vector<double> rate(sm.number_of_vertices(), 0.0);
  for (SurfaceMesh::Edge_index e : sm.edges()) {
    const SurfaceMesh::Vertex_index a = sm.vertex(e, 0), b = sm.vertex(e, 1);
    const double length = std::sqrt(CGAL::squared_distance(sm.point(a), sm.point(b)));
    if (!(length > 0.0)) continue;
    const double turn = std::acos(std::clamp(normal[std::size_t(a)] * normal[std::size_t(b)], -1.0, 1.0)) / length;
    rate[std::size_t(a)] = std::max(rate[std::size_t(a)], turn);
    rate[std::size_t(b)] = std::max(rate[std::size_t(b)], turn);
  }
  std::vector<double> ring = rate;
  for (SurfaceMesh::Edge_index e : sm.edges()) {
    const std::size_t a = std::size_t(sm.vertex(e, 0)), b = std::size_t(sm.vertex(e, 1));
    ring[a] = std::max(ring[a], rate[b]);
    ring[b] = std::max(ring[b], rate[a]);
  }
  return ring;
}

// Faces and edges of a coarse remeshing can bulge past the bound between vertices that keep it (a
// chord across a rounded crease): their vertices move towards the input by the excess, a few rounds.
void hold_faces_near(SurfaceMesh& sm, const Tree& input, double bound) {
  for (int round = 0; round < kHoldRounds; ++round) {
    std::vector<double> pull(sm.number_of_vertices(), 0.0);
    bool beyond = false;
    const auto sample = [&](const Point& p, std::initializer_list<SurfaceMesh::Vertex_index> corners) {
      const double d = std::sqrt(CGAL::squared_distance(p, input.closest_point(p)));
      if (d <= bound) return;
      beyond = true;
      for (SurfaceMesh::Vertex_index v : corners) pull[std::size_t(v)] = std::max(pull[std::size_t(v)], d - bound);
    };
    for (SurfaceMesh::Face_index f : sm.faces()) {
      const SurfaceMesh::Halfedge_index h = sm.halfedge(f);
      const SurfaceMesh::Vertex_index a = sm.source(h), b = sm.target(h), c = sm.target(sm.next(h));
      sample(CGAL::centroid(sm.point(a), sm.point(b), sm.point(c)), {a, b, c});
      sample(CGAL::midpoint(sm.point(a), sm.point(b)), {a, b});
    }
    if (!beyond) return;
    for (SurfaceMesh::Vertex_index v : sm.vertices()) {
      const double amount = kHoldOvershoot * pull[std::size_t(v)];
      if (!(amount > 0.0)) continue;
      const Point p = sm.point(v);
      const Point q = input.closest_point(p);
      const double d = std::sqrt(CGAL::squared_distance(p, q));
      sm.point(v) = d > amount ? p + (q - p) * (amount / d) : q;
    }
  }
}

// Rounds the creases over the crease radius: a diffusion of the vertices near them, the umbrella
// operator spreading a crease by about one edge per two steps of weight ½ (its variance grows by
// w·edge² per step). Smoothing alone leaves a dimple at a vertex of valence 3 (a box's corner), so
// every two steps a remeshing pass over the smoothed faces evens their triangles and valences; it
// ends early once no crease is left sharper than the shells take. Returns the steps taken.
int round_creases(SurfaceMesh& work, const Tree& tree, const RemeshOptions& options, double edge, int max_steps) {
  std::vector<Point> scratch;
  const double rings = options.crease_radius / edge;
  const int steps = std::min(max_steps, int(std::ceil(2.0 * rings * rings)));
  // Past the diffusion over the radius, only what is still sharper than the shells take (a saddle
  // where a hole meets a face) is smoothed on, up to kMaxExtraSteps more, while the sharpest crease
  // keeps easing (edges coarse against the radius never get under 20°; the surface would only
  // shrink to the bound).
  double crease_before = INFINITY;
  int done = 0;
  while (done < steps + kMaxExtraSteps) {
    const bool extra = done >= steps;
    if (extra) {
      const double crease = largest_crease(work);
      if (crease > crease_before - kExtraStepGainDegrees) break;
      crease_before = crease;
    }
    const std::vector<bool> marked =
        extra ? near_creases(work, kRemeshCreaseDegrees, 1) : near_creases(work, kRemeshCreaseDegrees, 2 * int(std::ceil(rings)));
    if (std::find(marked.begin(), marked.end(), true) == marked.end()) break;
    for (int k = 0; k < 2; ++k) {
      umbrella_step(work, marked, kSmoothingWeight, scratch);
      // The first step holds every vertex: the surface it starts from may not have been held yet.
      hold_near(work, tree, vertex_bound(options), done == 0 && k == 0 ? nullptr : &marked);
    }
    done += 2;
    even_triangles(work, faces_touching(work, marked), edge, tree, options);
  }
  return done;
}

// Where the surface is flat enough, coarser triangles: a vertex whose surroundings turn by κ rad/Å
// takes edges up to kTurnPerEdge / κ, and the faces whose three corners all take twice the edge are
// remeshed at it, level by level up to options.max_edge. The shells need no finer triangles where
// neighbouring faces turn by less than the creases they follow; a cell's flat side needs no 30 Å edge.
double coarsen(SurfaceMesh& work, const Tree& tree, const RemeshOptions& options) {
  double coarsest = options.edge;
  for (double edge = 2.0 * options.edge; edge <= options.max_edge * (1.0 + 1e-9); edge *= 2.0) {
    const std::vector<double> rate = vertex_turn_rates(work);
    // The border between the levels runs where the surface is flat, kBorderRings rings from anything
    // curved, so the long triangles CGAL fans onto its fine edges lie in one plane and make no crease.
    // Each level grows only out of the one just below it, so that its border meets edges half its own:
    // a 1 µm cube's faces fanned 1537 Å triangles onto 31 Å edges, slivers whose mending refined the
    // whole faces again.
    const MadeAt made = made_at(work);
    std::vector<bool> fine(work.number_of_vertices(), false);
    for (SurfaceMesh::Vertex_index v : work.vertices())
      fine[std::size_t(v)] = rate[std::size_t(v)] * edge > kTurnPerEdge || made[v] < kLowerLevelEdge * edge;
    grow_by_rings(work, fine, kBorderRings);
    std::vector<bool> coarse(fine.size());
    for (std::size_t v = 0; v < fine.size(); ++v) coarse[v] = !fine[v];
    std::vector<SurfaceMesh::Face_index> patch;
    for (SurfaceMesh::Face_index f : work.faces()) {
      bool all = true;
      for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(work.halfedge(f), work)) all = all && coarse[std::size_t(v)];
      if (all) patch.push_back(f);
    }
    if (patch.size() < kCoarsenAtLeast || !even_triangles(work, patch, edge, tree, options, 2)) break;
    coarsest = edge;
  }
  return coarsest;
}

// The angles (degrees) at corners a, b and c of a triangle; 0 at a corner with a zero-length side.
std::array<double, 3> corner_degrees(const Point& a, const Point& b, const Point& c) {
  const Point p[3] = {a, b, c};
  std::array<double, 3> degrees{};
  for (int k = 0; k < 3; ++k) {
    const Vector u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
    const double lu = std::sqrt(u.squared_length()), lv = std::sqrt(v.squared_length());
    degrees[k] = lu > 0.0 && lv > 0.0 ? std::acos(std::clamp(u * v / (lu * lv), -1.0, 1.0)) * kDegreesPerRadian : 0.0;
  }
  return degrees;
}

double smallest_angle(const Point& a, const Point& b, const Point& c) {
  const std::array<double, 3> degrees = corner_degrees(a, b, c);
  return *std::min_element(degrees.begin(), degrees.end());
}

// Whether face f is a sliver (an angle under kSliverMendDegrees) or a cap (one over kCapMendDegrees).
bool sliver_or_cap(const SurfaceMesh& sm, SurfaceMesh::Face_index f) {
  const SurfaceMesh::Halfedge_index h = sm.halfedge(f);
  const std::array<double, 3> degrees = corner_degrees(sm.point(sm.source(h)), sm.point(sm.target(h)), sm.point(sm.target(sm.next(h))));
  return std::any_of(degrees.begin(), degrees.end(), [](double d) { return d < kSliverMendDegrees || d > kCapMendDegrees; });
}

Vector unit_normal(const Point& a, const Point& b, const Point& c) {
  const Vector n = CGAL::cross_product(b - a, c - a);
  const double length = std::sqrt(n.squared_length());
  return length > 0.0 ? n / length : Vector(0, 0, 0);
}

double degrees_between(const Vector& a, const Vector& b) {
  return std::acos(std::clamp(a * b, -1.0, 1.0)) * kDegreesPerRadian;
}

// The halfedge of face f opposite its cap's corner (an angle over kCapMendDegrees), if it is a cap.
std::optional<SurfaceMesh::Halfedge_index> cap_base(const SurfaceMesh& sm, SurfaceMesh::Face_index f) {
  SurfaceMesh::Halfedge_index h = sm.halfedge(f);  // a→b; then b→c, c→a
  const std::array<double, 3> degrees = corner_degrees(sm.point(sm.source(h)), sm.point(sm.target(h)), sm.point(sm.target(sm.next(h))));
  // The corner at a faces b→c, at b faces c→a, at c faces a→b: k + 1 halfedges on from h.
  for (int k = 0; k < 3; ++k, h = sm.next(h))
    if (degrees[(k + 2) % 3] > kCapMendDegrees) return h;
  return std::nullopt;
}

// A cap lying flat with the face across its base (in a coarse level's plane, where CGAL's remeshing
// leaves a few) is mended by flipping that edge: the same surface, where remeshing around it would pick
// one size for two levels. Returns whether any was flipped.
bool flip_flat_caps(SurfaceMesh& sm) {
  bool any = false;
  for (SurfaceMesh::Face_index f : sm.faces()) {
    const std::optional<SurfaceMesh::Halfedge_index> base = cap_base(sm, f);
    if (!base || sm.is_border(sm.opposite(*base))) continue;
    const SurfaceMesh::Halfedge_index h = *base;
    const SurfaceMesh::Vertex_index a = sm.source(h), b = sm.target(h), c = sm.target(sm.next(h));
    const SurfaceMesh::Vertex_index d = sm.target(sm.next(sm.opposite(h)));
    if (CGAL::halfedge(c, d, sm).second) continue;
    const Point &pa = sm.point(a), &pb = sm.point(b), &pc = sm.point(c), &pd = sm.point(d);
    // The flipped faces (c,a,d) and (d,b,c) keep the plane and the orientation, and are better shaped.
    const Vector n = unit_normal(pa, pb, pc);
    const Vector n_other = unit_normal(pb, pa, pd), n_cad = unit_normal(pc, pa, pd), n_dbc = unit_normal(pd, pb, pc);
    if (degrees_between(n, n_other) > kFlatCapDegrees || degrees_between(n, n_cad) > kFlatCapDegrees ||
        degrees_between(n, n_dbc) > kFlatCapDegrees)
      continue;
    if (std::min(smallest_angle(pc, pa, pd), smallest_angle(pd, pb, pc)) <=
        std::min(smallest_angle(pa, pb, pc), smallest_angle(pb, pa, pd)))
      continue;
    CGAL::Euler::flip_edge(h, sm);
    any = true;
  }
  return any;
}

// Long thin triangles and caps left where levels meet or creases were refined (a check-mesh sliver, under
// 1°, stops the charts): flat caps are flipped, and the faces within two rings of what is left are
// remeshed at their own mean edge.
void mend_slivers(SurfaceMesh& work, const Tree& tree, const RemeshOptions& options) {
  for (int round = 0; round < kMendRounds; ++round) {
    for (int flips = 0; flips < kMendRounds; ++flips)
      if (!flip_flat_caps(work)) break;
    std::vector<bool> marked(work.number_of_vertices(), false);
    bool any = false;
    for (SurfaceMesh::Face_index f : work.faces())
      if (sliver_or_cap(work, f)) {
        any = true;
        for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(work.halfedge(f), work)) marked[std::size_t(v)] = true;
      }
    if (!any) return;
    grow_by_rings(work, marked, 2);
    const std::vector<SurfaceMesh::Face_index> patch = faces_touching(work, marked);
    double length = 0.0;
    std::size_t edges = 0;
    for (SurfaceMesh::Face_index f : patch)
      for (SurfaceMesh::Halfedge_index h : CGAL::halfedges_around_face(work.halfedge(f), work)) {
        length += std::sqrt(CGAL::squared_distance(work.point(work.source(h)), work.point(work.target(h))));
        ++edges;
      }
    if (!even_triangles(work, patch, edges ? length / double(edges) : options.edge, tree, options, 2)) return;
  }
}

}  // namespace

RemeshReport remesh_for_membrane(ProxyMesh& mesh, const RemeshOptions& options, const std::string& reason,
                                 const InputSource& source) {
  // Invariant, not input: a scene's "remesh" edge and check-mesh's --remesh are refused unless > 0
  // where they are read, and the bilayer's thickness likewise.
  if (!(options.edge > 0.0) || !(options.max_distance > 0.0))
    throw std::invalid_argument("remesh_for_membrane: the target edge and the distance bound must be positive");
  RemeshReport report;
  report.reason = reason;
  report.edge = options.edge;
  report.distance_bound = options.max_distance;
  report.triangles_in = mesh.triangles.size();
  const SurfaceMesh input = to_surface_mesh(mesh, source);
  report.largest_crease_in = largest_crease(input);
  report.area_in = PMP::area(input);
  report.volume_in = PMP::volume(input);
  Tree tree(faces(input).first, faces(input).second, input);
  tree.accelerate_distance_queries();

  SurfaceMesh work = input;
  PMP::isotropic_remeshing(faces(work), options.edge, work, CGAL::parameters::number_of_iterations(kRemeshIterations));
  work.collect_garbage();
  mark_new_vertices(work, options.edge);
  report.triangles_uniform = work.number_of_faces();
  // A large cell's first pass is coarser than half the bilayer: its creases get that edge first.
  const double fine = options.crease_edge > 0.0 ? std::min(options.crease_edge, options.edge) : options.edge;
  if (fine < options.edge) {
    const std::vector<bool> zone = near_creases(work, kRemeshCreaseDegrees, int(std::ceil(options.crease_radius / options.edge)) + 1);
    const std::vector<SurfaceMesh::Face_index> patch = faces_touching(work, zone);
    if (!patch.empty()) even_triangles(work, patch, fine, tree, options, 2, /*held=*/false);
  }
  report.crease_edge = fine;
  report.smoothing_steps = round_creases(work, tree, options, fine, kMaxSmoothingSteps);
  report.coarsest_edge = options.max_edge > options.edge ? coarsen(work, tree, options) : options.edge;
  // What the borders between the levels still fold is rounded and evened at the fine edge.
  if (report.coarsest_edge > options.edge && largest_crease(work) > kRemeshCreaseDegrees)
    report.smoothing_steps += round_creases(work, tree, options, fine, kBorderSmoothingSteps);
  // Holding the faces near the input moves vertices, which can crush a face into a sliver again
  // (fandisk at 3000 Å: four under 1° after one pass): mend and hold once more.
  for (int pass = 0; pass < 2; ++pass) {
    mend_slivers(work, tree, options);
    hold_faces_near(work, tree, options.max_distance);
  }
  report.largest_crease_out = largest_crease(work);
  report.area_out = PMP::area(work);
  report.volume_out = PMP::volume(work);

  // Distance and normal deviation at vertices, edge midpoints and face centroids of the new surface.
  auto measure = [&](const Point& p, const Vector* normal) {
    const auto [q, face] = tree.closest_point_and_primitive(p);
    report.max_distance = std::max(report.max_distance, std::sqrt(CGAL::squared_distance(p, q)));
    if (normal) {
      const Vector n = PMP::compute_face_normal(face, input);
      report.largest_normal_deviation =
          std::max(report.largest_normal_deviation, std::acos(std::clamp(n * *normal, -1.0, 1.0)) * kDegreesPerRadian);
    }
  };
  for (SurfaceMesh::Vertex_index v : work.vertices()) measure(work.point(v), nullptr);
  for (SurfaceMesh::Edge_index e : work.edges())
    measure(CGAL::midpoint(work.point(work.source(work.halfedge(e))), work.point(work.target(work.halfedge(e)))), nullptr);
  for (SurfaceMesh::Face_index f : work.faces()) {
    const SurfaceMesh::Halfedge_index h = work.halfedge(f);
    const Point c = CGAL::centroid(work.point(work.source(h)), work.point(work.target(h)),
                                   work.point(work.target(work.next(h))));
    const Vector n = PMP::compute_face_normal(f, work);
    measure(c, &n);
  }
  mesh = to_proxy_mesh(work);
  report.triangles_out = mesh.triangles.size();
  return report;
}

}  // namespace nano::mesh
