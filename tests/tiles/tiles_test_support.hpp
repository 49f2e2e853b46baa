#pragma once
#include <functional>
// Synthetic molecules and the independent oracle: explicit tilings and a grid-hash atom check that
// share no code with bake/tiles (own quaternion rotation, own hashing).
#include "bake/tiles/molecule_type.hpp"
#include "bake/tiles/tiling_recipe.hpp"
#include "bake/tiles/wang_set.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <algorithm>
#include <vector>

namespace nano::tiles::test {

// Small deterministic generator of the test's own (not the library's).
struct TestRng {
  uint64_t s;
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) * 0x1.0p-53;
  }
};

// A lipid-like stick: 40 atoms of radius 1.7 along z, head at +z, two tails, ~25 Å long.
inline MoleculeType make_lipid() {
  MoleculeType m{"lipid", {}, 0.f, {0.f, 0.f, 1.f}};
  for (int i = 0; i < 8; ++i)  // head group: a 2x2x2 cluster
    m.atoms.push_back({{(i & 1) ? 1.2f : -1.2f, (i & 2) ? 1.2f : -1.2f, (i & 4) ? 12.f : 10.4f}, 1.7f});
  for (int tail = 0; tail < 2; ++tail)
    for (int i = 0; i < 16; ++i)
      m.atoms.push_back({{tail ? 2.2f : -2.2f, 0.3f * std::sin(0.7f * i), 9.f - 1.4f * i}, 1.7f});
  return m;
}

// A blob of `count` atoms filling an ellipsoid with semi-axes (ax, ay, az), up axis +z.
inline MoleculeType make_blob(const std::string& name, int count, float ax, float ay, float az, uint64_t seed) {
  MoleculeType m{name, {}, 0.f, {0.f, 0.f, 1.f}};
  TestRng rng{seed};
  while (static_cast<int>(m.atoms.size()) < count) {
    const double x = 2 * rng.next() - 1, y = 2 * rng.next() - 1, z = 2 * rng.next() - 1;
    if (x * x + y * y + z * z > 1.0) continue;
    m.atoms.push_back({{float(x * ax), float(y * ay), float(z * az)}, 1.7f});
  }
  return m;
}

inline MoleculeType make_protein() { return make_blob("protein", 500, 25.f, 25.f, 25.f, 11); }
inline MoleculeType make_haemoglobin() { return make_blob("haemoglobin", 4500, 32.f, 28.f, 25.f, 12); }

// q v q* written out, independent of glm's matrix conversion.
inline glm::vec3 rotate(const glm::quat& q, const glm::vec3& v) {
  const glm::vec3 u(q.x, q.y, q.z);
  const glm::vec3 t = 2.f * glm::cross(u, v);
  return v + q.w * t + glm::cross(u, t);
}

struct WorldAtom {
  glm::vec3 centre;
  float radius;
  uint32_t copy;
  uint32_t type = 0;
};

struct ExplicitTiling {
  std::vector<WorldAtom> atoms;
  std::vector<size_t> copies_per_type;
  size_t copies = 0;
  bool ownership_ok = true;  // every instance centre in [0, edge) along lattice axes
};

// Where a surface puts a copy whose lattice-space centre is given: its position and the frame its
// atoms turn with (columns: tile x, y, z).
struct SurfacePlacement {
  glm::vec3 position;
  glm::mat3 frame{1.f};
};

// Place every cell's tile at its cell offset, every instance of it, every atom of the instances;
// `place` maps each copy's lattice-space centre onto a surface (identity by default).
inline ExplicitTiling instantiate(const WangSet& set, const TilingRecipe& recipe, const std::vector<MoleculeType>& types,
                                  bool with_atoms = true, const std::function<SurfacePlacement(glm::vec3)>& place = {}) {
  ExplicitTiling out;
  out.copies_per_type.assign(types.size(), 0);
  for (int k = 0; k < recipe.size[2]; ++k)
    for (int j = 0; j < recipe.size[1]; ++j)
      for (int i = 0; i < recipe.size[0]; ++i) {
        const WangTile& tile = set.tiles[recipe.at(i, j, k)];
        const glm::vec3 offset = set.edge * glm::vec3(i, j, set.dims == 3 ? k : 0);
        for (const Instance& in : tile.instances) {
          // Alternates overlap the copies they stand in for by design; the pruning decides them on
          // the real surface. The flat guarantee is the set proper's.
          if (in.alternate) continue;
          for (int a = 0; a < set.dims; ++a)
            if (!(in.position[a] >= 0.f && in.position[a] < set.edge)) out.ownership_ok = false;
          const uint32_t copy = static_cast<uint32_t>(out.copies++);
          ++out.copies_per_type[in.type];
          if (!with_atoms) continue;
          const SurfacePlacement at = place ? place(offset + in.position) : SurfacePlacement{offset + in.position};
          for (const AtomSphere& a : types[in.type].atoms)
            out.atoms.push_back({at.position + at.frame * rotate(in.rotation, a.centre), a.radius, copy, in.type});
        }
      }
  return out;
}

struct ClosePair {
  bool found = false;
  float distance = 0.f, limit = 0.f;
};

// Any two atoms of different copies closer than factor * (r1 + r2)? Dense cell grid (counting
// sort) over the atoms' box; each atom is compared with the atoms of its 27 neighbouring cells.
inline ClosePair find_close_pair(const std::vector<WorldAtom>& atoms, float factor) {
  if (atoms.empty()) return {};
  float rmax = 0.f;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const WorldAtom& a : atoms) {
    rmax = std::max(rmax, a.radius);
    lo = glm::min(lo, a.centre);
    hi = glm::max(hi, a.centre);
  }
  float cell = 2.f * rmax * factor + 1e-3f;
  const glm::vec3 extent = hi - lo + 1e-3f;
  while ((extent.x / cell + 1) * (extent.y / cell + 1) * (extent.z / cell + 1) > 2e7f) cell *= 1.25f;
  const glm::ivec3 dims = glm::ivec3(extent / cell) + 1;
  const auto cell_of = [&](const glm::vec3& c) { return glm::min(glm::ivec3((c - lo) / cell), dims - 1); };
  const auto index = [&](const glm::ivec3& g) { return (size_t(g.z) * dims.y + g.y) * dims.x + g.x; };
  std::vector<uint32_t> start(size_t(dims.x) * dims.y * dims.z + 1, 0), order(atoms.size());
  for (const WorldAtom& a : atoms) ++start[index(cell_of(a.centre)) + 1];
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (uint32_t i = 0; i < atoms.size(); ++i) order[fill[index(cell_of(atoms[i].centre))]++] = i;
  for (uint32_t i = 0; i < atoms.size(); ++i) {
    const glm::ivec3 g = cell_of(atoms[i].centre);
    for (int z = std::max(g.z - 1, 0); z <= std::min(g.z + 1, dims.z - 1); ++z)
      for (int y = std::max(g.y - 1, 0); y <= std::min(g.y + 1, dims.y - 1); ++y)
        for (int x = std::max(g.x - 1, 0); x <= std::min(g.x + 1, dims.x - 1); ++x) {
          const size_t c = index({x, y, z});
          for (uint32_t o = start[c]; o < start[c + 1]; ++o) {
            const uint32_t j = order[o];
            if (j <= i || atoms[j].copy == atoms[i].copy) continue;
            const float limit = factor * (atoms[i].radius + atoms[j].radius);
            const float d = glm::length(atoms[i].centre - atoms[j].centre);
            if (d < limit) return {true, d, limit};
          }
        }
  }
  return {};
}

// Every byte of a set that matters to the renderer, for identity checks.
inline std::vector<unsigned char> set_bytes(const WangSet& set) {
  std::vector<unsigned char> out;
  const auto put = [&](const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    out.insert(out.end(), b, b + n);
  };
  for (const WangTile& t : set.tiles) {
    put(&t.colours, sizeof t.colours);
    for (const Instance& in : t.instances) {
      put(&in.type, 4);
      put(&in.position, 12);
      put(&in.rotation, 16);
    }
    put(&t.atoms_min, 12);
    put(&t.atoms_max, 12);
  }
  return out;
}

}  // namespace nano::tiles::test
