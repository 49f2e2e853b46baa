#include "runtime/oracle/oracle_render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <atomic>

#include "common/error.hpp"
#include "common/parallel_for.hpp"
#include "format/package_view.hpp"
#include "runtime/placement/medium_rule.hpp"

namespace nano::oracle {
namespace {

using format::SectionKind;
using glm::dvec3;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Largest |centre| + radius over the atoms of any molecule type: every copy's atoms lie within
// this (times the instance stretch) of its origin.
double largest_type_radius(const format::Package& p) {
  const std::vector<double> radii = format::PackageView(p).atom_bounding_radii();
  return radii.empty() ? 0.0 : *std::max_element(radii.begin(), radii.end());
}

// Compartment-space box of everything compartment c can place. Generous on purpose: it only
// decides when a ray has left the scene, and a few hundred Å too many cost one empty round.
WorldBox compartment_reach(const format::Package& p, const gpu::Compartment& c, double type_radius) {
  WorldBox b{dvec3(kInf), dvec3(-kInf)};
  const auto add = [&](const dvec3& lo, const dvec3& hi) { b.min = glm::min(b.min, lo), b.max = glm::max(b.max, hi); };
  if (c.membrane_recipe != gpu::NANO_NO_INDEX) {
    const gpu::Mesh& mesh = p.records<SectionKind::meshes>()[c.mesh];
    const auto positions = p.records<SectionKind::vertex_positions>();
    const auto tiles = p.records<SectionKind::tiles2d>();
    const auto instances = p.records<SectionKind::instances>();
    double depth = 0;
    for (std::uint32_t t = c.membrane_first_tile; t < c.membrane_first_tile + c.membrane_tile_count; ++t)
      for (std::uint32_t m = tiles[t].first_instance; m < tiles[t].first_instance + tiles[t].instance_count; ++m)
        depth = std::max(depth, double(std::abs(instances[m].position.z)));
    const double grow = 2 * (depth + type_radius) + 100;
    for (std::uint32_t v = mesh.first_vertex; v < mesh.first_vertex + mesh.vertex_count; ++v)
      add(dvec3(positions[v]) - grow, dvec3(positions[v]) + grow);
  }
  if (c.soluble_recipe != gpu::NANO_NO_INDEX) {
    const dvec3 lo(c.grid_min);
    const dvec3 hi = lo + double(c.grid_min.w) * dvec3(glm::uvec3(c.grid_dims));
    const double grow = type_radius + 1 + 1e-3 * std::max(glm::length(lo), glm::length(hi));
    add(lo - grow, hi + grow);
  }
  return b;
}

WorldBox to_world(const format::InstanceTransform& t, const WorldBox& local) {
  WorldBox w{dvec3(kInf), dvec3(-kInf)};
  if (!(local.min.x <= local.max.x)) return w;
  for (int corner = 0; corner < 8; ++corner) {
    const dvec3 q((corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                  (corner & 4) ? local.max.z : local.min.z);
    const dvec3 out = t.linear * q + t.translation;
    w.min = glm::min(w.min, out), w.max = glm::max(w.max, out);
  }
  return w;
}

// One per compartment instance, standing where `transforms` put them.
std::vector<WorldBox> instance_bounds(const format::Package& p, const std::vector<format::InstanceTransform>& transforms) {
  const double type_radius = largest_type_radius(p);
  const auto compartments = p.records<SectionKind::compartments>();
  const auto instances = p.records<SectionKind::compartment_instances>();
  std::vector<WorldBox> boxes;
  for (std::size_t i = 0; i < instances.size(); ++i)
    boxes.push_back(to_world(transforms[i], compartment_reach(p, compartments[instances[i].compartment], type_radius)));
  return boxes;
}

std::vector<format::InstanceTransform> package_transforms(const format::Package& p) {
  std::vector<format::InstanceTransform> t;
  for (const gpu::CompartmentInstance& ci : p.records<SectionKind::compartment_instances>()) t.push_back(format::instance_transform(ci));
  return t;
}

double distance_to_box(const dvec3& p, const WorldBox& b) {
  if (!(b.min.x <= b.max.x)) return kInf;
  return glm::length(p - glm::clamp(p, b.min, b.max));
}

double farthest_corner(const dvec3& p, const WorldBox& b) {
  if (!(b.min.x <= b.max.x)) return 0;
  return glm::length(glm::max(glm::abs(b.min - p), glm::abs(b.max - p)));
}

// Upper bound of any copy's stretch: the Frobenius norm bounds the largest singular value.
double largest_instance_stretch(const std::vector<format::InstanceTransform>& transforms) {
  double s = 1;
  for (const format::InstanceTransform& t : transforms) {
    double f = 0;
    for (int c = 0; c < 3; ++c) f += glm::dot(t.linear[c], t.linear[c]);
    s = std::max(s, std::sqrt(f));
  }
  return s;
}

struct HeldAtom {
  dvec3 centre;
  double radius;
  std::uint32_t atom;
  std::uint32_t copy;  // index into the round's copies
};

struct HeldCopy {
  CopyId id;
  std::uint64_t number;
};

// The part of the view still to resolve: the pyramid from the eye over the ndc rectangle
// [x0, x1] × [y0, y1] (ray directions f + x·r + y·u, as camera_ray_direction builds them).
struct Pyramid {
  dvec3 eye, f, r, u;
  double x0, x1, y0, y1;
  dvec3 normals[4];  // inward side planes through the eye

  void make_planes() {
    const auto unit = [](const dvec3& v) { return v / glm::length(v); };
    normals[0] = unit(r - x0 * f), normals[1] = unit(x1 * f - r);
    normals[2] = unit(u - y0 * f), normals[3] = unit(y1 * f - u);
  }
  // Conservative: the slack covers the float rounding of camera_ray_direction (≈ 1e-7 rad) many
  // times over, so a ray of the rectangle is never outside.
  bool meets_sphere(const dvec3& c, double radius, double depth_bound) const {
    const dvec3 v = c - eye;
    const double dist = glm::length(v);
    const double slack = 1e-3 + 1e-6 * dist;
    if (dist - radius > depth_bound + slack) return false;
    for (const dvec3& n : normals)
      if (glm::dot(n, v) < -radius - slack) return false;
    return true;
  }
  // Every point eye + t·ŵ with 0 ≤ t ≤ D and w in the rectangle is eye + s·w with s = t/|w| ≤ D
  // (|w| ≥ 1), so it lies in the pyramid over the rectangle of height D, whose box is spanned by
  // the apex and the four far corners.
  WorldBox box(double depth_bound) const {
    WorldBox b{eye, eye};
    for (double x : {x0, x1})
      for (double y : {y0, y1}) {
        const dvec3 p = eye + depth_bound * (f + x * r + y * u);
        b.min = glm::min(b.min, p), b.max = glm::max(b.max, p);
      }
    return b;
  }
};

struct Ray {
  dvec3 o, d, inv;
};

double sphere_hit(const Ray& ray, const dvec3& centre, double radius) { return first_sphere_hit(ray.o, ray.d, centre, radius); }

// A median-split BVH over atom spheres: enough for ≤ 3e7 spheres and a few hundred thousand rays.
class AtomBvh {
public:
  explicit AtomBvh(std::vector<HeldAtom>& atoms) : atoms_(atoms) {
    if (atoms_.empty()) return;
    nodes_.reserve(2 * atoms_.size() / kLeaf + 1);
    build(0, std::uint32_t(atoms_.size()));
  }

  // Nearest hit with t ≤ t_max: index into atoms and t, or (−1, +inf).
  std::pair<std::int64_t, double> trace(const Ray& ray, double t_max, const std::vector<HeldCopy>& copies) const {
    std::int64_t best = -1;
    double best_t = kInf;
    if (nodes_.empty()) return {best, best_t};
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (box_entry(ray, n, std::min(t_max, best_t)) == kInf) continue;
      if (n.count > 0) {
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
          const HeldAtom& a = atoms_[i];
          const double t = sphere_hit(ray, a.centre, a.radius);
          if (t > t_max || t > best_t) continue;
          if (t == best_t && !less(a, atoms_[best], copies)) continue;
          best = i, best_t = t;
        }
        continue;
      }
      // Nearer child last, so it is popped first and shrinks best_t for the other.
      const std::uint32_t a = n.first, b = n.first + 1;
      const double ta = box_entry(ray, nodes_[a], best_t), tb = box_entry(ray, nodes_[b], best_t);
      if (ta <= tb) stack[top++] = b, stack[top++] = a;
      else stack[top++] = a, stack[top++] = b;
    }
    return {best, best_t};
  }

private:
  static constexpr std::uint32_t kLeaf = 4;
  struct Node {
    dvec3 lo, hi;
    std::uint32_t first = 0;  // leaf: first atom; inner: left child (right = first + 1)
    std::uint32_t count = 0;  // atoms in a leaf, 0 for an inner node
  };

  static bool less(const HeldAtom& a, const HeldAtom& b, const std::vector<HeldCopy>& copies) {
    const std::uint64_t ca = copies[a.copy].number, cb = copies[b.copy].number;
    return ca != cb ? ca < cb : a.atom < b.atom;
  }

  // Entry t of the slab test over [0, t_max], +inf on a miss. Zero direction components are
  // decided from the origin alone: (lo − o)·∞ would be NaN when the origin lies on the slab.
  static double box_entry(const Ray& ray, const Node& n, double t_max) {
    double t0 = 0, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
      if (ray.d[a] == 0) {
        if (ray.o[a] < n.lo[a] || ray.o[a] > n.hi[a]) return kInf;
        continue;
      }
      double ta = (n.lo[a] - ray.o[a]) * ray.inv[a], tb = (n.hi[a] - ray.o[a]) * ray.inv[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb * (1 + 1e-12));
      if (t0 > t1) return kInf;
    }
    return t0;
  }

  void build(std::uint32_t first, std::uint32_t count) {
    struct Task {
      std::uint32_t node, first, count;
    };
    nodes_.push_back({});
    std::vector<Task> tasks{{0, first, count}};
    while (!tasks.empty()) {
      const Task task = tasks.back();
      tasks.pop_back();
      dvec3 lo(kInf), hi(-kInf), clo(kInf), chi(-kInf);
      for (std::uint32_t i = task.first; i < task.first + task.count; ++i) {
        const HeldAtom& a = atoms_[i];
        lo = glm::min(lo, a.centre - a.radius), hi = glm::max(hi, a.centre + a.radius);
        clo = glm::min(clo, a.centre), chi = glm::max(chi, a.centre);
      }
      nodes_[task.node].lo = lo, nodes_[task.node].hi = hi;
      if (task.count <= kLeaf) {
        nodes_[task.node].first = task.first, nodes_[task.node].count = task.count;
        continue;
      }
      const dvec3 extent = chi - clo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      const std::uint32_t half = task.count / 2;
      const auto begin = atoms_.begin() + task.first;
      std::nth_element(begin, begin + half, begin + task.count,
                       [axis](const HeldAtom& a, const HeldAtom& b) { return a.centre[axis] < b.centre[axis]; });
      const std::uint32_t left = std::uint32_t(nodes_.size());
      nodes_.push_back({}), nodes_.push_back({});
      nodes_[task.node].first = left;
      tasks.push_back({left, task.first, half});
      tasks.push_back({left + 1, task.first + half, task.count - half});
    }
  }

  std::vector<HeldAtom>& atoms_;
  std::vector<Node> nodes_;
};

gpu::PixelHit make_hit(double t, std::uint32_t atom, const CopyId& id, std::uint64_t number) {
  gpu::PixelHit h;
  h.depth = float(t);
  h.compartment_instance = id.compartment_instance;
  h.element = id.element;
  h.kind = std::uint32_t(id.kind);
  h.cell = glm::ivec4(id.cell, 0);
  h.instance = id.instance;
  h.atom = atom;
  h.copy_number_lo = std::uint32_t(number);
  h.copy_number_hi = std::uint32_t(number >> 32);
  return h;
}

// The medium along each pixel's ray, traced apart from the rounds (their pyramid boxes would hold
// billions of its copies) and independently of the renderer's DDA: the ray is sampled every box B
// within the region grown by two boxes and on the kept side of every clip half-space; each sample's
// box and the boxes within two of it give their kept copies (the shared keep rule) and every atom
// of a copy whose sphere the ray meets (the enumerator skips boxes wholly inside an instance).
// Why two: a copy reaches one box beyond its own, so a point of the ray inside one of its atoms lies
// in a box within one of the copy's, and the sample nearest that point (at most B/2 along the ray,
// so per axis) in a box within one more. Sampling stops half a box beyond the nearest hit.
}  // namespace
gpu::PixelHit background_pixel();
namespace {

// The nearest atom a ray meets so far; exact ties go to the lower copy number, then atom (AtomBvh's rule).
struct NearestHit {
  double t = kInf;
  std::uint32_t atom = 0;
  CopyId id;
  std::uint64_t number = 0;
  void offer(double t_hit, std::uint32_t atom_hit, const CopyId& copy, std::uint64_t copy_number) {
    if (t_hit > t) return;
    if (t_hit == t && !(copy_number < number || (copy_number == number && atom_hit < atom))) return;
    *this = {t_hit, atom_hit, copy, copy_number};
  }
};

// The kept copies of the medium's boxes, each box enumerated once for a chunk of neighbouring rays
// (which visit mostly the same boxes) instead of once per ray: the same copies, in the same order,
// with the box that holds their spheres (grown by `grow`, the radius scale beyond 1), so a ray that
// misses it skips the box's copies without a test each.
class MediumBoxCopies {
public:
  struct Box {
    std::vector<Copy> copies;
    WorldBox spheres{dvec3(kInf), dvec3(-kInf)};
  };
  MediumBoxCopies(const ExplicitScene& scene, double grow) : scene_(scene), grow_(grow) {}
  const Box& of(const glm::ivec3& box, std::uint64_t key) {
    auto [entry, fresh] = kept_.try_emplace(key);
    if (fresh)
      scene_.for_each_medium_copy(box, [&](const Copy& c) {
        entry->second.copies.push_back(c);
        WorldBox& spheres = entry->second.spheres;
        spheres.min = glm::min(spheres.min, c.origin - c.radius * grow_);
        spheres.max = glm::max(spheres.max, c.origin + c.radius * grow_);
      });
    return entry->second;
  }

private:
  const ExplicitScene& scene_;
  double grow_;
  std::unordered_map<std::uint64_t, Box> kept_;
};

// Where the ray (t ≥ 0) is inside the box: [entry, exit], or nothing.
std::optional<std::pair<double, double>> ray_box(const Ray& ray, const WorldBox& b) {
  double t0 = 0, t1 = kInf;
  for (int a = 0; a < 3; ++a) {
    if (ray.d[a] == 0) {
      if (ray.o[a] < b.min[a] || ray.o[a] > b.max[a]) return std::nullopt;
      continue;
    }
    double ta = (b.min[a] - ray.o[a]) * ray.inv[a], tb = (b.max[a] - ray.o[a]) * ray.inv[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return std::nullopt;
  return std::pair(t0, t1);
}

NearestHit trace_medium_ray(const format::PackageView& p, const Ray& ray, const OracleRenderOptions& options,
                            MediumBoxCopies& box_copies) {
  const gpu::Medium& m = p.medium[0];
  const double B = m.region_min.w;
  const dvec3 lo = dvec3(m.region_min) - 2.0 * B, hi = dvec3(m.region_max) + 2.0 * B;
  const auto region = ray_box(ray, WorldBox{lo, hi});
  if (!region) return {};
  auto [t0, t1] = *region;
  // The kept side of each half-space, widened by two boxes (a kept atom's copy may stand beyond it).
  for (const glm::dvec4& h : options.clip) {
    const double along = glm::dot(dvec3(h), ray.d), at = glm::dot(dvec3(h), ray.o) + h.w + 4.0 * B;
    if (along == 0) {
      if (at < 0) return {};
    } else if (along > 0) {
      t0 = std::max(t0, -at / along);
    } else {
      t1 = std::min(t1, -at / along);
    }
  }
  if (!(t0 <= t1)) return {};
  NearestHit best;
  const glm::ivec3 boxes(glm::uvec3(m.boxes));
  const auto visit_box = [&](const glm::ivec3& b) {
    if (glm::any(glm::lessThan(b, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(b, boxes))) return;
    const std::uint64_t key = std::uint64_t(b.x) + std::uint64_t(boxes.x) * (std::uint64_t(b.y) + std::uint64_t(boxes.y) * std::uint64_t(b.z));
    const MediumBoxCopies::Box& box = box_copies.of(b, key);
    if (!ray_box(ray, box.spheres)) return;
    for (const Copy& c : box.copies) {
      if (sphere_hit(ray, c.origin, c.radius * std::max(1.0, options.radius_scale)) == kInf) continue;
      const gpu::MoleculeType& type = p.molecules[c.molecule_type];
      for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
        const dvec3 centre_a = c.origin + c.linear * dvec3(p.atoms[a].centre_radius);
        bool clipped = false;
        for (const glm::dvec4& h : options.clip) clipped = clipped || !(glm::dot(dvec3(h), centre_a) + h.w >= 0);
        if (clipped) continue;
        best.offer(sphere_hit(ray, centre_a, p.atoms[a].centre_radius.w * c.stretch * options.radius_scale), a, c.id, c.number);
      }
    }
  };
  // A ray moves the same way along each axis, so the windows of the samples slide one way: a box in
  // this sample's window that an earlier window held is in the previous one's (no set of seen boxes).
  bool first = true;
  glm::ivec3 previous(0);
  const auto in_window = [](const glm::ivec3& b, const glm::ivec3& centre) {
    return glm::all(glm::lessThanEqual(glm::abs(b - centre), glm::ivec3(2)));
  };
  for (double t = t0; t <= t1 && t <= best.t + B / 2; t += B) {
    const glm::ivec3 cell(glm::floor((ray.o + t * ray.d - dvec3(m.region_min)) / B));
    if (!first && cell == previous) continue;
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const glm::ivec3 b = cell + glm::ivec3(dx, dy, dz);
          if (first || !in_window(b, previous)) visit_box(b);
        }
    first = false;
    previous = cell;
  }
  return best;
}

// The medium's hit of each pixel of `pixels` (background where it has none, and at every other pixel).
std::vector<gpu::PixelHit> trace_medium(const ExplicitScene& scene, const format::Package& package, const std::vector<Ray>& rays,
                                        const std::vector<std::uint32_t>& pixels, const OracleRenderOptions& options) {
  std::vector<gpu::PixelHit> image(rays.size(), background_pixel());
  const format::PackageView p(package);
  constexpr std::size_t kChunk = 64;
  parallel_for((pixels.size() + kChunk - 1) / kChunk, static_cast<int>(std::max(1u, options.threads)), [&](std::size_t chunk) {
    MediumBoxCopies box_copies(scene, std::max(1.0, options.radius_scale));
    for (std::size_t i = chunk * kChunk; i < std::min(pixels.size(), (chunk + 1) * kChunk); ++i) {
      const NearestHit hit = trace_medium_ray(p, rays[pixels[i]], options, box_copies);
      if (hit.t != kInf) image[pixels[i]] = make_hit(hit.t, hit.atom, hit.id, hit.number);
    }
  });
  return image;
}

std::string count(double v);


// Where the ray runs through some compartment instance's reach (boxes holding every atom, grown
// by `grow`): sorted, overlapping spans merged. Outside them no compartment atom can be hit.
std::vector<std::pair<double, double>> reach_spans(const Ray& ray, const std::vector<WorldBox>& reach, double grow) {
  std::vector<std::pair<double, double>> spans;
  for (const WorldBox& b : reach)
    if (const auto span = ray_box(ray, WorldBox{b.min - grow, b.max + grow})) spans.push_back(*span);
  std::sort(spans.begin(), spans.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& span : spans) {
    if (!merged.empty() && span.first <= merged.back().second) merged.back().second = std::max(merged.back().second, span.second);
    else merged.push_back(span);
  }
  return merged;
}

constexpr double kTubeSegment = 32.0;  // Å of ray per box query: keeps the boxes tight around the ray

// One pixel's compartment hit with t ≤ t_end, its ray alone: segment by segment along the spans,
// every atom whose centre lies within `grow` of the segment's box. A hit at t ≤ the segment's end is
// final: an atom hit at t' ≤ that end has its hit point on a segment already queried (within the
// spans) and its centre within its radius of it.
NearestHit trace_tube(const ExplicitScene& scene, const format::Package& package, const Ray& ray,
                   const std::vector<std::pair<double, double>>& spans, double grow, double t_end,
                   const OracleRenderOptions& options, std::atomic<std::uint64_t>& segments) {
  NearestHit best;
  for (const auto& [from, to] : spans)
    for (double t0 = from; t0 <= std::min({to, t_end, best.t}); t0 += kTubeSegment) {
      if (++segments > options.max_tube_segments)
        throw InputError(package.name(), "camera " + options.camera_name,
                         "the CPU oracle would need more than " + count(double(options.max_tube_segments)) +
                             " ray segments to resolve the view; choose a camera that sees less (closer, narrower)");
      const double t1 = std::min(to, t0 + kTubeSegment);
      const dvec3 a = ray.o + t0 * ray.d, b = ray.o + t1 * ray.d;
      scene.for_each_compartment_atom(WorldBox{glm::min(a, b) - grow, glm::max(a, b) + grow}, [&](const AtomSample& s) {
        for (const glm::dvec4& h : options.clip)
          if (!(glm::dot(dvec3(h), s.position) + h.w >= 0)) return;
        best.offer(sphere_hit(ray, s.position, s.radius * options.radius_scale), s.atom, s.copy->id, s.copy->number);
      });
      if (best.t <= t1) return best;
    }
  return best;
}

// A round's atoms would not fit: its pixels go to ray tubes.
struct RoundTooLarge {};

std::string count(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// One render's state across its rounds: what every step reads (the scene, the eye's rays, the
// instances' reach, the medium's hits) and what the steps fill (the image, the unresolved pixels).
struct DeepeningRender {
  const ExplicitScene& scene;
  const format::Package& package;
  const gpu::Camera& camera;
  const OracleRenderOptions& options;
  OracleRenderStats& st;
  std::vector<gpu::PixelHit>& image;
  std::vector<Ray> rays;
  std::vector<WorldBox> bounds;
  double grow = 0;  // the largest atom reach from a copy's origin, over every instance stretch
  std::vector<gpu::PixelHit> medium_hits;
  std::vector<std::uint32_t> pending;

  double medium_depth(std::uint32_t p) const {
    return medium_hits.empty() || medium_hits[p].atom == gpu::kNoHit ? kInf : double(medium_hits[p].depth);
  }
  int threads() const { return static_cast<int>(std::max(1u, options.threads)); }
};

Pyramid eye_pyramid(const gpu::Camera& camera) {
  Pyramid view;
  view.eye = dvec3(glm::vec3(camera.position));
  view.f = dvec3(glm::vec3(camera.forward));
  view.r = dvec3(glm::vec3(camera.right));
  view.u = dvec3(glm::vec3(camera.up));
  return view;
}

std::vector<Ray> camera_rays(const gpu::Camera& camera, const dvec3& eye) {
  const std::uint32_t width = camera.size.x, height = camera.size.y;
  std::vector<Ray> rays(std::size_t(width) * height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      Ray& ray = rays[std::size_t(y) * width + x];
      ray.o = eye;
      ray.d = dvec3(gpu::camera_ray_direction(camera, x, y));
      ray.d /= glm::length(ray.d);
      ray.inv = 1.0 / ray.d;
    }
  return rays;
}

// A ray through no instance's reach meets no compartment atom: its medium hit or nothing, now. The
// others stay pending.
void resolve_rays_out_of_reach(DeepeningRender& r, const std::vector<std::uint32_t>& pixels) {
  for (const std::uint32_t p : pixels) {
    if (!reach_spans(r.rays[p], r.bounds, r.grow).empty()) r.pending.push_back(p);
    else if (std::isfinite(r.medium_depth(p))) r.image[p] = r.medium_hits[p];
  }
}

// The pixels left when a round cannot hold their atoms: each through its own ray's tube.
void trace_tubes(DeepeningRender& r) {
  std::atomic<std::uint64_t> segments{0};
  const double tube_grow = r.grow * std::max(1.0, r.options.radius_scale);
  constexpr std::size_t kTubeChunk = 8;
  parallel_for((r.pending.size() + kTubeChunk - 1) / kTubeChunk, r.threads(), [&](std::size_t chunk) {
    for (std::size_t i = chunk * kTubeChunk; i < std::min(r.pending.size(), (chunk + 1) * kTubeChunk); ++i) {
      const std::uint32_t p = r.pending[i];
      const double medium_t = r.medium_depth(p);
      const NearestHit hit = trace_tube(r.scene, r.package, r.rays[p], reach_spans(r.rays[p], r.bounds, tube_grow), tube_grow,
                                        medium_t, r.options, segments);
      if (hit.t <= medium_t && hit.t != kInf) r.image[p] = make_hit(hit.t, hit.atom, hit.id, hit.number);
      else if (std::isfinite(medium_t)) r.image[p] = r.medium_hits[p];
    }
  });
  r.st.tube_rays = r.pending.size();
  r.st.tube_segments = segments;
  r.pending.clear();
}

// Narrows the pyramid to the ndc rectangle of the pending pixels (as camera_ray_direction computes
// a pixel's ndc coordinates, before normalising), widened past the float rounding.
void fit_pyramid_to_pending(Pyramid& view, const DeepeningRender& r) {
  const gpu::Camera& camera = r.camera;
  const std::uint32_t width = camera.size.x, height = camera.size.y;
  view.x0 = view.y0 = kInf, view.x1 = view.y1 = -kInf;
  for (std::uint32_t p : r.pending) {
    const std::uint32_t x = p % width, y = p / width;
    const glm::dvec2 n((2.0 * (x + 0.5) / width - 1.0) * camera.forward.w * camera.right.w,
                       (1.0 - 2.0 * (y + 0.5) / height) * camera.forward.w);
    view.x0 = std::min(view.x0, n.x), view.x1 = std::max(view.x1, n.x);
    view.y0 = std::min(view.y0, n.y), view.y1 = std::max(view.y1, n.y);
  }
  const double widen = 1e-6 * (1 + camera.forward.w * (1 + camera.right.w));
  view.x0 -= widen, view.x1 += widen, view.y0 -= widen, view.y1 += widen;
  view.make_planes();
}

// Every compartment atom that can meet the pyramid up to depth_bound, with its copy. Throws
// RoundTooLarge past the atom cap when ray tubes may take over, InputError when they may not.
void hold_round_atoms(const DeepeningRender& r, const Pyramid& view, double depth_bound, std::vector<HeldAtom>& atoms,
                      std::vector<HeldCopy>& copies) {
  const OracleRenderOptions& options = r.options;
  WorldBox box = view.box(depth_bound);
  box.min -= r.grow, box.max += r.grow;
  atoms.clear(), copies.clear();
  r.scene.for_each_compartment_atom(box, [&](const AtomSample& s) {
    // Clipping keeps or removes an atom whole, by its centre (as the renderer).
    for (const glm::dvec4& h : options.clip)
      if (!(glm::dot(dvec3(h), s.position) + h.w >= 0)) return;
    if (!view.meets_sphere(s.position, s.radius * std::max(1.0, options.radius_scale), depth_bound)) return;
    // A copy's atoms arrive consecutively and copy numbers are unique.
    if (copies.empty() || copies.back().number != s.copy->number) copies.push_back({s.copy->id, s.copy->number});
    if (atoms.size() >= options.max_atoms && options.ray_tubes) throw RoundTooLarge{};
    if (atoms.size() >= options.max_atoms)
      throw InputError(r.package.name(), "camera " + options.camera_name,
                       "the CPU oracle would need more than " + count(double(options.max_atoms)) +
                           " atoms to resolve the view up to " + count(depth_bound) +
                           " Å from the eye; choose a camera that sees less (closer, narrower) or raise the atom cap");
    atoms.push_back({s.position, s.radius * options.radius_scale, s.atom, std::uint32_t(copies.size() - 1)});
  });
}

// Traces the pending pixels against the round's atoms (which the BVH reorders) up to depth_bound;
// those with a hit (an atom's or the medium's) there are final and leave the pending list.
void trace_round(DeepeningRender& r, std::vector<HeldAtom>& atoms, const std::vector<HeldCopy>& copies,
                 double depth_bound) {
  const AtomBvh bvh(atoms);
  std::vector<std::uint8_t> resolved(r.pending.size(), 0);
  constexpr std::size_t kChunk = 64;
  parallel_for((r.pending.size() + kChunk - 1) / kChunk, r.threads(), [&](std::size_t chunk) {
    for (std::size_t i = chunk * kChunk; i < std::min(r.pending.size(), (chunk + 1) * kChunk); ++i) {
      const std::uint32_t p = r.pending[i];
      const auto [hit, t] = bvh.trace(r.rays[p], depth_bound, copies);
      const double medium_t = r.medium_depth(p);
      if (hit >= 0 && t <= medium_t) {
        const HeldCopy& c = copies[atoms[hit].copy];
        r.image[p] = make_hit(t, atoms[hit].atom, c.id, c.number);
      } else if (medium_t <= depth_bound) {
        r.image[p] = r.medium_hits[p];
      } else {
        continue;
      }
      resolved[i] = 1;
    }
  });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < r.pending.size(); ++i)
    if (!resolved[i]) r.pending[kept++] = r.pending[i];
  r.pending.resize(kept);
}

}  // namespace

gpu::PixelHit background_pixel() {
  gpu::PixelHit h;
  h.depth = std::numeric_limits<float>::infinity();
  h.compartment_instance = h.element = h.kind = h.instance = h.atom = gpu::kNoHit;
  h.copy_number_lo = h.copy_number_hi = gpu::kNoHit;
  h.cell = glm::ivec4(int(gpu::kNoHit));
  return h;
}

WorldBox scene_world_bounds(const format::Package& package, const ExplicitScene* scene) {
  WorldBox all{dvec3(kInf), dvec3(-kInf)};
  for (const WorldBox& b : instance_bounds(package, scene ? scene->instance_transforms() : package_transforms(package))) all.min = glm::min(all.min, b.min), all.max = glm::max(all.max, b.max);
  return all;
}

// Progressive deepening. Round k holds every atom that can meet the pyramid of the still
// unresolved pixels up to depth D_k and traces those pixels with t ≤ D_k. Such a hit is final:
// any atom hit by the ray at t ≤ D_k has its hit point in that pyramid, so its centre lies in the
// pyramid's box grown by the largest atom radius (what for_each_atom is asked for, ExplicitScene
// culling conservatively by copy spheres), its sphere passes the plane and depth tests of
// Pyramid::meets_sphere, and it was held and tested. A pixel with no hit up to D_k stays
// unresolved and D doubles, until D passes the farthest corner of the scene's bounds: then
// nothing is left to hit and the pixel is background.
std::vector<gpu::PixelHit> oracle_render(const ExplicitScene& scene, const format::Package& package,
                                         const gpu::Camera& camera, const OracleRenderOptions& options,
                                         OracleRenderStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<gpu::PixelHit> image(std::size_t(camera.size.x) * camera.size.y, background_pixel());
  OracleRenderStats local_stats;
  OracleRenderStats& st = stats ? *stats : local_stats;
  st = {};
  if (image.empty()) return image;

  Pyramid view = eye_pyramid(camera);
  DeepeningRender r{scene, package, camera, options, st, image, camera_rays(camera, view.eye),
                    instance_bounds(package, scene.instance_transforms())};
  double nearest = kInf, farthest = 0;
  for (const WorldBox& b : r.bounds) nearest = std::min(nearest, distance_to_box(view.eye, b)), farthest = std::max(farthest, farthest_corner(view.eye, b));
  const double near_depth = std::isfinite(nearest) ? nearest : 0;
  r.grow = largest_type_radius(package) * largest_instance_stretch(scene.instance_transforms()) + 1e-3;
  double depth_bound = near_depth + options.first_margin;

  // The medium first: a pixel whose medium hit lies within a round's depth bound is resolved by that
  // round whether or not a compartment atom comes nearer, so the rounds stop where the plasma does.
  std::vector<std::uint32_t> pixels = options.only_pixels;
  if (pixels.empty()) {
    pixels.resize(image.size());
    for (std::uint32_t p = 0; p < pixels.size(); ++p) pixels[p] = p;
  }
  for (const std::uint32_t p : pixels)
    if (p >= image.size()) throw InputError(package.name(), "camera " + options.camera_name, "pixel " + std::to_string(p) + " is outside the image");
  if (scene.has_medium()) r.medium_hits = trace_medium(scene, package, r.rays, pixels, options);
  resolve_rays_out_of_reach(r, pixels);
  if (options.tubes_only) trace_tubes(r);
  std::vector<HeldAtom> atoms;
  std::vector<HeldCopy> copies;
  while (!r.pending.empty() && farthest > 0) {
    ++st.rounds;
    fit_pyramid_to_pending(view, r);
    try {
      hold_round_atoms(r, view, depth_bound, atoms, copies);
    } catch (const RoundTooLarge&) {
      trace_tubes(r);
      break;
    }
    st.atoms_last_round = atoms.size();
    st.atoms_total += atoms.size();
    st.final_depth_bound = depth_bound;
    trace_round(r, atoms, copies, depth_bound);
    if (depth_bound >= farthest) break;  // nothing lies beyond: the rest is background
    // Deeper by twice as much beyond the nearest instance: a far eye does not jump the whole
    // distance it already stands away (its pyramid would hold every cell in view).
    depth_bound = near_depth + 2 * (depth_bound - near_depth);
  }
  for (std::uint32_t p : r.pending)
    if (!r.medium_hits.empty() && r.medium_hits[p].atom != gpu::kNoHit) image[p] = r.medium_hits[p];
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

double first_sphere_hit(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& centre, double radius) {
  const dvec3 f = origin - centre;
  const double beta = glm::dot(f, direction);
  const dvec3 l = f - beta * direction;
  const double dist = glm::length(l);
  if (dist > radius) return kInf;
  const double disc = (radius - dist) * (radius + dist);
  const double c = glm::dot(f, f) - radius * radius;
  const double q = -(beta + (beta >= 0 ? std::sqrt(disc) : -std::sqrt(disc)));
  double t0 = -beta, t1 = -beta;
  if (q != 0) t0 = c / q, t1 = q;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 >= 0) return t0;
  return t1 >= 0 ? t1 : kInf;
}

}  // namespace nano::oracle
