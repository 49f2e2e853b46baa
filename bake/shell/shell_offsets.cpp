#include "bake/shell/shell_offsets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <string>

#include "bake/grid/triangle_distance.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"

namespace nano::shell {

namespace {

constexpr double kMinNormalCos = 0.1;   // vertex normals tilted > 84° from the face: treat as 84°
constexpr int kMaxGrowIterations = 64;
constexpr double kGrowSlack = 1e-3;     // Å added per growth step so float rounding cannot stall it

struct Sphere {
  glm::dvec3 centre;
  double radius;
  glm::dvec3 bary;  // barycentrics of uv_m
  std::uint32_t type;
  std::uint32_t key;  // MembraneMapping::copy_key
  bool alternate;     // listed means shown for an alternate (membrane_copy_listed_shows): never dropped here
};

struct Plane {  // inside: dot(normal, x) <= offset
  glm::dvec3 normal;
  double offset;
  double margin(const glm::dvec3& p) const { return offset - glm::dot(normal, p); }
};

// Five conservative half-spaces of the prism (see header): bottom, top, walls 0..2.
std::array<Plane, 5> prism_half_spaces(const gpu::Prism& pr) {
  std::array<glm::dvec3, 6> v;
  for (int i = 0; i < 6; ++i) v[i] = glm::dvec3(pr.v[i]);
  glm::dvec3 centroid(0.0);
  for (const glm::dvec3& p : v) centroid += p / 6.0;
  auto oriented = [&](glm::dvec3 n, const glm::dvec3* corners, int count) {
    n = glm::normalize(n);
    glm::dvec3 mid(0.0);
    for (int i = 0; i < count; ++i) mid += corners[i] / double(count);
    if (glm::dot(n, mid - centroid) < 0.0) n = -n;
    double off = glm::dot(n, corners[0]);
    for (int i = 1; i < count; ++i) off = std::min(off, glm::dot(n, corners[i]));
    return Plane{n, off};
  };
  std::array<Plane, 5> h;
  const glm::dvec3 bottom[3] = {v[0], v[1], v[2]};
  const glm::dvec3 top[3] = {v[3], v[4], v[5]};
  h[0] = oriented(glm::cross(v[1] - v[0], v[2] - v[0]), bottom, 3);
  h[1] = oriented(glm::cross(v[4] - v[3], v[5] - v[3]), top, 3);
  for (int w = 0; w < 3; ++w) {
    const int j = (w + 1) % 3;
    const glm::dvec3 c[4] = {v[w], v[j], v[w + 3], v[j + 3]};
    // Normal of the bilinear patch at (½, ½): mean u-edge × mean v-edge.
    h[2 + w] = oriented(glm::cross((c[1] - c[0]) + (c[3] - c[2]), (c[2] - c[0]) + (c[3] - c[1])), c, 4);
  }
  return h;
}

// prism_intersect parity from p in three fixed, non-axis directions; true only if all say inside.
bool point_inside(const gpu::Prism& pr, const glm::dvec3& p) {
  static const glm::vec3 dirs[3] = {{0.267f, 0.535f, 0.802f}, {-0.707f, 0.123f, -0.697f}, {0.455f, -0.873f, 0.176f}};
  for (const glm::vec3& d : dirs) {
    gpu::PrismInterval r;
    gpu::prism_intersect(pr, glm::vec3(p), d, 0.f, gpu::placement_inf(), r);
    if (!r.origin_inside) return false;
  }
  return true;
}

}  // namespace

float molecule_origin_radius(const tiles::MoleculeType& type) {
  double r = 0.0;
  for (const tiles::AtomSphere& a : type.atoms)
    r = std::max(r, glm::length(glm::dvec3(a.centre)) + double(a.radius));
  // Rounded up so the float radius is never smaller than the double one.
  float f = static_cast<float>(r);
  if (double(f) < r) f = std::nextafter(f, INFINITY);
  return f;
}

gpu::ShellOffsets fixed_offsets(const std::vector<gpu::ShellOffsets>& offsets) {
  gpu::ShellOffsets f{0.f, 0.f, 0.f};
  for (const gpu::ShellOffsets& o : offsets) f = gpu::shell_offsets_max(f, o);
  return f;
}

gpu::Prism triangle_prism(const MembraneMapping& mapping, std::size_t t, const gpu::ShellOffsets& offsets) {
  const TriangleMapping& tm = mapping.triangle(t);
  return gpu::shell_prism_make(tm.position[0], tm.position[1], tm.position[2], tm.normal[0], tm.normal[1],
                               tm.normal[2], offsets);
}

namespace {

// What one block of triangles contributes besides its offsets.
struct BlockTotals {
  ShellStats stats;
  std::vector<std::size_t> owned_by_type;
  std::vector<std::size_t> dropped_by_type;
  std::vector<std::uint32_t> uncontained, lipids_left_out;
};

void merge(ShellStats& into, const ShellStats& s) {
  into.owned_molecules += s.owned_molecules;
  into.triangles_with_molecules += s.triangles_with_molecules;
  into.grown_triangles += s.grown_triangles;
  into.max_grow_iterations = std::max(into.max_grow_iterations, s.max_grow_iterations);
  into.uncontained_triangles += s.uncontained_triangles;
  into.unfit_triangles += s.unfit_triangles;
  into.inverted_caps += s.inverted_caps;
  into.min_vertex_normal_cos = std::min(into.min_vertex_normal_cos, s.min_vertex_normal_cos);
}

struct PrismFit {
  gpu::ShellOffsets offsets{0.f, 0.f, 0.f};
  int iterations = 0;
  bool contained = false;
};

// Offsets of triangle t's prism that contain `spheres`: estimated, then verified and grown.
PrismFit fit_prism(const MembraneMapping& mapping, std::size_t t, const std::vector<Sphere>& spheres, double cmin) {
  const TriangleMapping& tm = mapping.triangle(t);
  const glm::dvec3 p0(tm.position[0]), p1(tm.position[1]), p2(tm.position[2]);
  const glm::dvec3 face = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  // Altitude onto the edge opposite corner k: 2·area / |edge|.
  const double area2 = glm::length(glm::cross(p1 - p0, p2 - p0));
  const glm::dvec3 alt(area2 / glm::length(p2 - p1), area2 / glm::length(p0 - p2), area2 / glm::length(p1 - p0));

  // Maxima of the numerators, divided once: a rounded division by cmin > 0 never decreases as
  // its numerator grows, so this is bit for bit the maximum of the quotients.
  double hp = 0.0, hm = 0.0, side = 0.0;
  for (const Sphere& s : spheres) {
    const double z = glm::dot(s.centre - p0, face);
    hp = std::max(hp, z + s.radius);
    hm = std::max(hm, s.radius - z);
    for (int k = 0; k < 3; ++k) side = std::max(side, s.radius - s.bary[k] * alt[k]);
  }

  PrismFit fit;
  gpu::ShellOffsets& off = fit.offsets;
  off = {float(hp / cmin), float(hm / cmin), float(side / cmin)};
  for (; fit.iterations <= kMaxGrowIterations; ++fit.iterations) {
    const gpu::Prism pr = triangle_prism(mapping, t, off);
    const std::array<Plane, 5> hs = prism_half_spaces(pr);
    double deficit[5] = {0, 0, 0, 0, 0};
    for (const Sphere& s : spheres)
      for (int f = 0; f < 5; ++f)
        deficit[f] = std::max(deficit[f], s.radius + kShellContainmentMargin - hs[f].margin(s.centre));
    const double wall = std::max(deficit[2], std::max(deficit[3], deficit[4]));
    if (deficit[0] <= 0.0 && deficit[1] <= 0.0 && wall <= 0.0) {
      fit.contained = point_inside(pr, spheres.front().centre);
      break;
    }
    if (deficit[0] > 0.0) off.h_minus = float(off.h_minus + deficit[0] / cmin + kGrowSlack);
    if (deficit[1] > 0.0) off.h_plus = float(off.h_plus + deficit[1] / cmin + kGrowSlack);
    if (wall > 0.0) off.side = float(off.side + wall / cmin + kGrowSlack);
  }
  return fit;
}

// Drops droppable copies from `spheres`, largest first, until a prism contains the rest; only then are
// their keys added to `dropped` (ascending) and counted. Not contained when none is left to drop.
PrismFit fit_without_unfit(const MembraneMapping& mapping, std::size_t t, std::vector<Sphere> spheres, double cmin,
                           const std::vector<bool>& droppable, std::vector<std::uint32_t>& dropped,
                           std::vector<std::size_t>& dropped_by_type) {
  std::vector<Sphere> left_out;
  for (;;) {
    std::size_t largest = spheres.size();
    for (std::size_t i = 0; i < spheres.size(); ++i)
      if (!spheres[i].alternate && spheres[i].type < droppable.size() && droppable[spheres[i].type] &&
          (largest == spheres.size() || spheres[i].radius > spheres[largest].radius))
        largest = i;
    if (largest == spheres.size() || spheres.size() == 1) return PrismFit{};
    left_out.push_back(spheres[largest]);
    spheres.erase(spheres.begin() + std::ptrdiff_t(largest));
    const PrismFit fit = fit_prism(mapping, t, spheres, cmin);
    if (!fit.contained) continue;
    for (const Sphere& s : left_out) {
      dropped.push_back(s.key);
      ++dropped_by_type[s.type];
    }
    std::sort(dropped.begin(), dropped.end());
    return fit;
  }
}

// How far the spheres not in `dropped` (ascending keys) reach from triangle t (see ShellResult::reach).
float kept_reach(const MembraneMapping& mapping, std::size_t t, const std::vector<Sphere>& spheres,
                 const std::vector<std::uint32_t>& dropped) {
  const TriangleMapping& tm = mapping.triangle(t);
  const glm::dvec3 p0(tm.position[0]), p1(tm.position[1]), p2(tm.position[2]);
  double reach = 0.0;
  bool any = false;
  for (const Sphere& s : spheres) {
    if (!s.alternate && std::binary_search(dropped.begin(), dropped.end(), s.key)) continue;
    reach = std::max(reach, std::sqrt(grid::squared_distance_to_triangle(s.centre, p0, p1, p2)) + s.radius);
    any = true;
  }
  return any ? static_cast<float>(reach + kShellContainmentMargin) : 0.f;
}

// Triangles [begin, end): their offsets and reach into `out`, the rest into `totals`.
void shell_block(const MembraneMapping& mapping, const std::vector<double>& radius, const std::vector<bool>& droppable,
                 std::size_t begin, std::size_t end, ShellResult& out, BlockTotals& totals) {
  std::vector<gpu::ShellOffsets>& offsets = out.offsets;
  std::vector<std::vector<std::uint32_t>>& dropped = out.dropped;
  const std::size_t type_count = radius.size();
  ShellStats& stats = totals.stats;
  totals.owned_by_type.assign(type_count, 0);
  totals.dropped_by_type.assign(type_count, 0);
  std::vector<Sphere> spheres;
  for (std::size_t t = begin; t < end; ++t) {
    spheres.clear();
    mapping.for_each_owned_membrane_place(t, [&](const OwnedPlace& m) {
      if (m.type >= type_count)
        throw InputError("shell", "tile " + std::to_string(m.tile) + " instance " + std::to_string(m.instance),
                         "molecule type " + std::to_string(m.type) + " is not among the " +
                             std::to_string(type_count) + " types given");
      const bool alternate = mapping.set().tiles[m.tile].instances[m.instance].alternate;
      if (!alternate) ++totals.owned_by_type[m.type];
      spheres.push_back({glm::dvec3(mapping.centre_of(t, m)), radius[m.type],
                         glm::dvec3(gpu::chart_barycentric(mapping.triangle(t).chart, m.uv)), m.type,
                         mapping.copy_key(t, m), alternate});
    });
    if (spheres.empty()) continue;  // offsets stay zero: a flat prism the runtime can skip
    stats.owned_molecules += spheres.size();
    stats.triangles_with_molecules += 1;

    const TriangleMapping& tm = mapping.triangle(t);
    const glm::dvec3 p0(tm.position[0]), p1(tm.position[1]), p2(tm.position[2]);
    const glm::dvec3 face = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    double cmin = 1.0;
    for (int c = 0; c < 3; ++c) cmin = std::min(cmin, glm::dot(glm::dvec3(tm.normal[c]), face));
    stats.min_vertex_normal_cos = std::min(stats.min_vertex_normal_cos, cmin);
    cmin = std::max(cmin, kMinNormalCos);

    PrismFit fit = fit_prism(mapping, t, spheres, cmin);
    if (!fit.contained && !droppable.empty()) {
      const PrismFit without = fit_without_unfit(mapping, t, spheres, cmin, droppable, dropped[t], totals.dropped_by_type);
      if (without.contained) {
        fit = without;
        stats.unfit_triangles += 1;
      }
    }
    if (fit.iterations > 0) stats.grown_triangles += 1;
    stats.max_grow_iterations = std::max(stats.max_grow_iterations, fit.iterations);
    if (!fit.contained) {
      stats.uncontained_triangles += 1;
      totals.uncontained.push_back(static_cast<std::uint32_t>(t));
      PrismFit without = fit_without_unfit(mapping, t, spheres, cmin, std::vector<bool>(type_count, true), dropped[t],
                                           totals.dropped_by_type);
      if (!without.contained) {  // not even one copy: the triangle is left empty (a flat prism)
        for (const Sphere& s : spheres)
          if (!s.alternate) {
            dropped[t].push_back(s.key);
            ++totals.dropped_by_type[s.type];
          }
        std::sort(dropped[t].begin(), dropped[t].end());
        dropped[t].erase(std::unique(dropped[t].begin(), dropped[t].end()), dropped[t].end());
        without = PrismFit{{0.f, 0.f, 0.f}, 0, true};
      }
      fit = without;
      totals.lipids_left_out.push_back(static_cast<std::uint32_t>(t));
    }

    // The prism contract of ray_prism.h: neither cap may face against the face normal.
    const gpu::Prism pr = triangle_prism(mapping, t, fit.offsets);
    const glm::dvec3 nb = glm::cross(glm::dvec3(pr.v[1] - pr.v[0]), glm::dvec3(pr.v[2] - pr.v[0]));
    const glm::dvec3 nt = glm::cross(glm::dvec3(pr.v[4] - pr.v[3]), glm::dvec3(pr.v[5] - pr.v[3]));
    if (!(glm::dot(nb, face) > 0.0) || !(glm::dot(nt, face) > 0.0)) stats.inverted_caps += 1;
    offsets[t] = fit.offsets;
    out.reach[t] = kept_reach(mapping, t, spheres, dropped[t]);
  }
}

}  // namespace

ShellResult compute_shell_offsets(const MembraneMapping& mapping, const std::vector<tiles::MoleculeType>& types,
                                  int threads, const std::vector<bool>& droppable) {
  std::vector<double> radius(types.size());
  for (std::size_t i = 0; i < types.size(); ++i) radius[i] = molecule_origin_radius(types[i]);

  ShellResult out;
  const std::size_t n = mapping.triangle_count();
  out.offsets.assign(n, gpu::ShellOffsets{0.f, 0.f, 0.f});
  out.dropped.assign(n, {});
  out.reach.assign(n, 0.f);
  const std::size_t blocks =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), 1, std::max<std::size_t>(n, 1));
  std::vector<BlockTotals> totals(blocks);
  // A block stops at its first failing triangle; parallel_for rethrows the lowest block's error.
  parallel_for(blocks, threads, [&](std::size_t b) {
    shell_block(mapping, radius, droppable, n * b / blocks, n * (b + 1) / blocks, out, totals[b]);
  });
  out.owned_by_type.assign(types.size(), 0);
  out.dropped_by_type.assign(types.size(), 0);
  for (const BlockTotals& block : totals) {
    merge(out.stats, block.stats);
    for (std::size_t i = 0; i < types.size(); ++i) {
      out.owned_by_type[i] += block.owned_by_type[i];
      out.dropped_by_type[i] += block.dropped_by_type[i];
    }
    out.uncontained.insert(out.uncontained.end(), block.uncontained.begin(), block.uncontained.end());
    out.lipids_left_out.insert(out.lipids_left_out.end(), block.lipids_left_out.begin(), block.lipids_left_out.end());
  }
  out.fixed = fixed_offsets(out.offsets);
  return out;
}

}  // namespace nano::shell
