#include "bake/grid/soluble_masks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "bake/grid/triangle_distance.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"

namespace nano::grid {

namespace {

constexpr const char* context = "soluble keep-masks";

std::uint32_t words_for(std::size_t molecules) { return static_cast<std::uint32_t>((molecules + 31) / 32); }

std::uint32_t cube_of(const CubeRecipe& recipe, const glm::ivec3& b, std::size_t cube_count) {
  const std::uint32_t c = recipe(b);
  if (c >= cube_count)
    throw InputError(context, "recipe", "cube index " + std::to_string(c) + " for box (" + std::to_string(b.x) + ", " +
                                            std::to_string(b.y) + ", " + std::to_string(b.z) + ") is out of range");
  return c;
}

void validate_cubes(const std::vector<CubeContents>& cubes, double box_size, double shell_clearance, double clearance) {
  if (!(shell_clearance >= 0.0) || !std::isfinite(shell_clearance))
    throw InputError(context, "shell clearance", "must be finite and not negative");
  if (cubes.empty()) throw InputError(context, "cubes", "no Wang cubes");
  for (std::size_t c = 0; c < cubes.size(); ++c)
    for (std::size_t m = 0; m < cubes[c].size(); ++m) {
      const CubeMolecule& mol = cubes[c][m];
      const std::string where = "cube " + std::to_string(c) + " molecule " + std::to_string(m);
      for (int a = 0; a < 3; ++a)
        if (!(mol.centre[a] >= 0.0 && mol.centre[a] < box_size))
          throw InputError(context, where, "centre outside the cube [0, S)^3");
      if (!(mol.radius >= 0.0) || !std::isfinite(mol.radius))
        throw InputError(context, where, "bounding radius must be finite and not negative");
      if (shell_clearance + mol.radius > clearance)
        throw InputError(context, where, "shell clearance + radius exceeds the grid clearance: INSIDE boxes would hold molecules too close to the surface");
    }
}

// Decides the molecules of one BOUNDARY box and writes its mask words; returns the kept count.
std::uint32_t decide_box(const MeshSurface& surface, const CoreGrid& grid, const glm::ivec3& b, const CubeContents& cube,
                         double shell_clearance, std::uint32_t* words) {
  double reach = 0.0;  // largest required clearance of a molecule centre in this cube
  for (const CubeMolecule& m : cube) reach = std::max(reach, m.radius + shell_clearance);
  const glm::dvec3 lo = grid.box_min(b), hi = lo + grid.box_size, centre = grid.box_centre(b);
  // Any triangle within `reach` of a centre in the box meets the box grown by reach.
  const std::vector<std::uint32_t> local = surface.triangles_meeting(lo - reach, hi + reach);
  const mesh::ProxyMesh& mesh = surface.mesh();
  int centre_inside = -1;  // lazily queried
  std::uint32_t kept = 0;
  for (std::size_t m = 0; m < cube.size(); ++m) {
    const glm::dvec3 p = lo + cube[m].centre;
    const double need = cube[m].radius + shell_clearance;
    double d2 = std::numeric_limits<double>::infinity();
    for (std::uint32_t t : local) {
      const mesh::Triangle& tri = mesh.triangles[t];
      d2 = std::min(d2, squared_distance_to_triangle(p, mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]));
      if (d2 < need * need) break;
    }
    if (d2 < need * need) continue;
    // The open ball of radius min(local distance, reach) around p holds no surface point, so
    // the box centre, when inside that ball, is on p's side.
    const double free_radius = std::min(std::sqrt(d2), reach);
    bool inside;
    if (glm::length(p - centre) < free_radius) {
      if (centre_inside < 0) centre_inside = surface.contains(centre) ? 1 : 0;
      inside = centre_inside == 1;
    } else {
      inside = surface.contains(p);
    }
    if (!inside) continue;
    words[m / 32] |= std::uint32_t{1} << (m % 32);
    ++kept;
  }
  return kept;
}

}  // namespace

std::size_t KeepMasks::bytes() const {
  return boundary_boxes.size() * sizeof(BoxIndex) + word_offsets.size() * sizeof(std::uint32_t) +
         words.size() * sizeof(std::uint32_t);
}

std::span<const std::uint32_t> KeepMasks::mask_of(BoxIndex box) const {
  const auto it = std::lower_bound(boundary_boxes.begin(), boundary_boxes.end(), box);
  if (it == boundary_boxes.end() || *it != box) return {};
  const std::size_t n = static_cast<std::size_t>(it - boundary_boxes.begin());
  return {words.data() + word_offsets[n], words.data() + word_offsets[n + 1]};
}

KeepMasks compute_keep_masks(const MeshSurface& surface, const BoxOccupancy& occupancy,
                             const std::vector<CubeContents>& cubes, const CubeRecipe& recipe,
                             double shell_clearance, int threads) {
  const CoreGrid& grid = occupancy.grid;
  validate_cubes(cubes, grid.box_size, shell_clearance, occupancy.clearance);

  KeepMasks masks;
  std::vector<std::uint32_t> box_cube;  // cube of each BOUNDARY box; the recipe is called serially
  masks.boundary_boxes.reserve(occupancy.boundary);
  box_cube.reserve(occupancy.boundary);
  masks.word_offsets.reserve(occupancy.boundary + 1);
  std::uint64_t total_words = 0;
  for (std::size_t i = 0; i < occupancy.classes.size(); ++i) {
    if (occupancy.classes[i] != BoxClass::boundary) continue;
    const BoxIndex box = static_cast<BoxIndex>(i);
    const std::uint32_t c = cube_of(recipe, grid.box_at(box), cubes.size());
    masks.boundary_boxes.push_back(box);
    box_cube.push_back(c);
    masks.word_offsets.push_back(static_cast<std::uint32_t>(total_words));
    total_words += words_for(cubes[c].size());
    if (total_words > std::numeric_limits<std::uint32_t>::max())
      throw InputError(context, "masks", "more than 2^32 mask words");
  }
  masks.word_offsets.push_back(static_cast<std::uint32_t>(total_words));
  masks.words.assign(total_words, 0u);

  // Boxes go to the threads in chunks; each chunk writes only its own boxes' words.
  constexpr std::size_t kChunk = 64;
  const std::size_t chunks = (masks.boundary_boxes.size() + kChunk - 1) / kChunk;
  std::vector<std::uint64_t> kept(chunks, 0), total(chunks, 0);
  parallel_for(chunks, threads, [&](std::size_t chunk) {
    for (std::size_t n = chunk * kChunk; n < std::min(masks.boundary_boxes.size(), (chunk + 1) * kChunk); ++n) {
      const CubeContents& cube = cubes[box_cube[n]];
      kept[chunk] += decide_box(surface, grid, grid.box_at(masks.boundary_boxes[n]), cube, shell_clearance,
                                masks.words.data() + masks.word_offsets[n]);
      total[chunk] += cube.size();
    }
  });
  for (std::size_t c = 0; c < chunks; ++c) {
    masks.kept += kept[c];
    masks.dropped += total[c] - kept[c];
  }
  return masks;
}

std::vector<std::uint64_t> represented_copies(const BoxOccupancy& occupancy, const std::vector<CubeContents>& cubes,
                                              const CubeRecipe& recipe, const KeepMasks& masks) {
  if (masks.boundary_boxes.size() != occupancy.boundary || masks.word_offsets.size() != masks.boundary_boxes.size() + 1)
    throw InputError(context, "masks", "keep-masks do not belong to this occupancy");
  std::uint32_t types = 0;
  for (const CubeContents& cube : cubes)
    for (const CubeMolecule& m : cube) types = std::max(types, m.type + 1);
  std::vector<std::uint64_t> copies(types, 0);

  // INSIDE boxes: count them per cube, then multiply by the cube's per-type counts.
  std::vector<std::uint64_t> inside_per_cube(cubes.size(), 0);
  for (std::size_t i = 0; i < occupancy.classes.size(); ++i)
    if (occupancy.classes[i] == BoxClass::inside)
      ++inside_per_cube[cube_of(recipe, occupancy.grid.box_at(static_cast<BoxIndex>(i)), cubes.size())];
  for (std::size_t c = 0; c < cubes.size(); ++c)
    for (const CubeMolecule& m : cubes[c]) copies[m.type] += inside_per_cube[c];

  for (std::size_t n = 0; n < masks.boundary_boxes.size(); ++n) {
    const CubeContents& cube = cubes[cube_of(recipe, occupancy.grid.box_at(masks.boundary_boxes[n]), cubes.size())];
    const std::uint32_t* words = masks.words.data() + masks.word_offsets[n];
    for (std::size_t m = 0; m < cube.size(); ++m)
      if (words[m / 32] >> (m % 32) & 1u) ++copies[cube[m].type];
  }
  return copies;
}

}  // namespace nano::grid
