#include "tests/oracle/hand_scene.hpp"

#include <cmath>
#include <cstring>

namespace nano::explicit_test {
namespace {

using glm::dvec3;
using glm::uvec4;
using glm::vec2;
using glm::vec4;

format::AtomInfo info(const char* chain, const char* residue, int number, const char* name, const char* element) {
  format::AtomInfo a{};
  std::memcpy(a.chain, chain, std::strlen(chain));
  std::memcpy(a.residue_name, residue, std::strlen(residue));
  std::memcpy(a.atom_name, name, std::strlen(name));
  std::memcpy(a.element, element, std::strlen(element));
  a.residue_number = number;
  return a;
}

vec4 quat(dvec3 axis, double degrees) {
  const glm::dquat q = glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
  return vec4(float(q.x), float(q.y), float(q.z), float(q.w));
}

gpu::MoleculeInstance molecule(glm::vec3 position, vec4 rotation, std::uint32_t type) {
  // The tile-space AABB is not used by placement; a loose one keeps the validator content.
  return {rotation, vec4(position, 0), vec4(position - 10.0f, 0), vec4(position + 10.0f, 0), type, 0, 0, 0};
}

// Rotation of a unit quaternion stored (x, y, z, w), in double.
glm::dmat3 rotation_of(const vec4& q) { return glm::mat3_cast(glm::dquat(q.w, q.x, q.y, q.z)); }

// The compartment-instance transform exactly as the package stores it (float rows), in double.
struct Rigid {
  glm::dmat3 linear;
  dvec3 translation;
  dvec3 operator()(const dvec3& p) const { return linear * p + translation; }
};
Rigid stored_transform(const gpu::CompartmentInstance& ci) {
  Rigid r;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) r.linear[col][row] = ci.transform[row][col];
    r.translation[row] = ci.transform[row][3];
  }
  return r;
}

void add_square_mesh(SampleScene& s, bool mirrored) {
  const std::uint32_t first_vertex = std::uint32_t(s.vertex_positions.size());
  const std::uint32_t first_triangle = std::uint32_t(s.triangles.size());
  const float L = float(kL), k = float(kK);
  for (vec2 xy : {vec2(0, 0), vec2(L, 0), vec2(L, L), vec2(0, L)}) {
    s.vertex_positions.push_back(vec4(xy, 0, 0));
    s.vertex_normals.push_back(vec4(0, 0, 1, 0));
    s.vertex_uvs.push_back(vec2(mirrored ? L - xy.x : xy.x, xy.y) / k);
  }
  // Both triangles use the diagonal (0,0)-(L,L), the shared edge molecules are placed on.
  s.triangles.push_back({0, 1, 2});
  s.triangles.push_back({0, 2, 3});
  for (int t = 0; t < 2; ++t) s.triangle_shells.push_back({vec4(0, 0, 2, 2), 8.0f, 8.0f, 1.0f, 0});
  s.meshes.push_back({vec4(0, 0, 0, 0), vec4(L, L, 0, 0), first_vertex, 4, first_triangle, 2});
}

gpu::Compartment membrane_compartment(std::uint32_t mesh) {
  gpu::Compartment c{};
  c.scales = vec4(float(kK), float(kS), float(kBox), 0);
  c.mesh = mesh;
  c.membrane_first_tile = 0;
  c.membrane_tile_count = 2;
  c.membrane_recipe = 0;
  c.soluble_recipe = gpu::NANO_NO_INDEX;
  // UV box [0, 2]² with s = 1/2: origin floor(0 − slack) = −1, extent 4 + 2 = 6 cells per axis.
  c.replication_width = c.replication_height = 6;
  return c;
}

// Core grid tables, shared by the scene and its oracle.
constexpr glm::ivec3 kGridDims(3, 2, 2);
const glm::vec3 kGridMin(-40, -20, 10);
constexpr std::uint8_t I = gpu::NANO_BOX_INSIDE, O = gpu::NANO_BOX_OUTSIDE, B = gpu::NANO_BOX_BOUNDARY;
constexpr std::uint8_t kOccupancy[12] = {I, O, B, I, B, I, B, I, I, I, O, B};
// Keep-mask word of each BOUNDARY box above (largest cube: 2 molecules, so one word per box).
const std::map<int, std::uint32_t> kKeep = {{2, 0b10u}, {4, 0b10u}, {6, 0b00u}, {11, 0b11u}};

}  // namespace

std::vector<Placement> default_placements() {
  return {{0, {0, 0, 1}, 0, {0, 0, 0}},
          {1, {0, 0, 1}, 0, {0, 0, 500}},
          {0, {1, 2, 3}, 40, {1000, -500, 250}},
          {2, {0, 0, 1}, 90, {0, 300, 0}}};
}

SampleScene hand_scene(const std::vector<Placement>& placements) {
  SampleScene s;
  // Type 0: three atoms, asymmetric so a wrong rotation shows; type 1: one atom at its origin.
  s.atoms = {{vec4(-1.5f, 0, 0, 1.2f)}, {vec4(1.5f, 0, 0, 1.2f)}, {vec4(0, 1, 0.5f, 1)}, {vec4(0, 0, 0, 2)}};
  s.atom_info = {info("A", "LYS", 42, "N", "N"), info("A", "LYS", 42, "CA", "C"), info("A", "LYS", 43, "O", "O"),
                 info("B", "HEM", 1, "FE", "FE")};
  s.molecules = {{vec4(-2.7f, -1.2f, -1.2f, 2.7f), vec4(2.7f, 2, 1.5f, 0), vec4(0, 0, 1, 0), vec4(1, 0, 0, 1), 0, 3, 0, 0, 0, 0, 0, 0},
                 {vec4(-2, -2, -2, 2), vec4(2, 2, 2, 0), vec4(0, 0, 1, 0), vec4(0, 1, 0, 1), 3, 1, 0, 0, 0, 0, 0, 0}};
  // Wang squares 0 and 1 (checkerboard recipe). Square 0: a general molecule, one on the cell's
  // diagonal (on the triangles' shared edge in cells a = b), one at the cell corner (on the edge,
  // on every cell line, and on the chart's outer boundary), one on the cell's bottom line.
  // Square 1: one molecule.
  s.instances = {molecule({8, 4, 3}, quat({0, 0, 1}, 30), 0), molecule({20, 20, 0}, quat({1, 1, 0}, 60), 1),
                 molecule({0, 0, -2}, quat({1, 0, 0}, 90), 0), molecule({12, 0, 1}, quat({0, 1, 0}, 0), 0),
                 molecule({5, 27, 2}, quat({0, 1, 1}, 120), 0)};
  s.tiles2d = {{uvec4(0), vec4(float(kS), float(kS), 10, 0), 0, 4, 0, 0}, {uvec4(0), vec4(float(kS), float(kS), 10, 0), 4, 1, 0, 0}};
  // Wang cubes: 0 is unused so the compartment's cube set starts at 1 (recipe indices are absolute
  // tile indices, docs/format.md); cubes 1 and 2 hold two molecules each.
  s.instances.push_back(molecule({5, 5, 5}, quat({1, 0, 0}, 45), 0));
  s.instances.push_back(molecule({15, 10, 2.5f}, quat({0, 0, 1}, 0), 1));
  s.instances.push_back(molecule({10, 10, 10}, quat({2, -1, 1}, 75), 0));
  s.instances.push_back(molecule({19.5f, 0.5f, 10}, quat({0, 0, 1}, -30), 0));  // atoms reach into boxes +x and −y
  const vec4 cube_size{float(kBox), float(kBox), float(kBox), 0.0f};
  s.tiles3d = {{uvec4(0), uvec4(0), cube_size, 5, 1, 0, 0}, {uvec4(0), uvec4(0), cube_size, 5, 2, 0, 0},
               {uvec4(0), uvec4(0), cube_size, 7, 2, 0, 0}};
  s.recipes = {{uvec4(2, 2, 1, gpu::NANO_RECIPE_2D), 0, 4, 0, 0}, {uvec4(2, 1, 1, gpu::NANO_RECIPE_3D), 4, 2, 0, 0}};
  s.recipe_indices = {0, 1, 1, 0, 1, 2};

  add_square_mesh(s, false);
  add_square_mesh(s, true);
  s.compartments = {membrane_compartment(0), membrane_compartment(1)};
  gpu::Compartment core{};
  core.grid_min = vec4(kGridMin, float(kBox));
  core.grid_dims = uvec4(kGridDims, 0);
  core.scales = vec4(float(kK), float(kS), float(kBox), 0);
  core.membrane_recipe = gpu::NANO_NO_INDEX;
  core.soluble_first_tile = 1;
  core.soluble_tile_count = 2;
  core.soluble_recipe = 1;
  core.core_masks = uvec4(0, std::uint32_t(kKeep.size()), 0, 0);
  s.compartments.push_back(core);
  s.occupancy.assign(std::begin(kOccupancy), std::end(kOccupancy));
  for (const auto& [box, word] : kKeep) {
    s.boundary_boxes.push_back({std::uint32_t(box), std::uint32_t(s.mask_words.size())});
    s.mask_words.push_back(word);
  }

  s.scene = {{vec4(64, 64, 400, 0.8f), vec4(64, 64, 0, 0), vec4(0, 1, 0, 0), 0, 0, 0, 0}};  // sections_of writes every kind
  for (const Placement& p : placements) {
    const glm::dmat3 r = glm::mat3_cast(glm::angleAxis(glm::radians(p.degrees), glm::normalize(p.axis)));
    gpu::CompartmentInstance ci{};
    for (int row = 0; row < 3; ++row)
      ci.transform[row] = vec4(float(r[0][row]), float(r[1][row]), float(r[2][row]), float(p.translation[row]));
    ci.compartment = p.compartment;
    s.compartment_instances.push_back(ci);
  }
  return s;
}

Expected expected_atoms(const SampleScene& s, const std::vector<Placement>& placements) {
  Expected out;
  auto add_copy = [&](AtomKey key, const Rigid& world, dvec3 origin, const glm::dmat3& rotation, const gpu::MoleculeInstance& m) {
    const gpu::MoleculeType& type = s.molecules[m.molecule_type];
    for (std::uint32_t a = type.first_atom; a < type.first_atom + type.atom_count; ++a) {
      key.atom = a;
      out[key] = {world(origin + rotation * dvec3(s.atoms[a].centre_radius)), s.atoms[a].centre_radius.w};
    }
  };
  for (std::uint32_t ci = 0; ci < placements.size(); ++ci) {
    const Rigid world = stored_transform(s.compartment_instances[ci]);
    const std::uint32_t comp = placements[ci].compartment;
    if (comp <= 1) {
      const bool mirrored = comp == 1;
      const double s_uv = kS / kK;
      for (int b = -3; b < 8; ++b)
        for (int a = -3; a < 8; ++a) {
          const int tile = (a + b) % 2 == 0 ? 0 : 1;  // recipe 0 1 / 1 0 wrapped: a checkerboard
          const gpu::Tile2D& square = s.tiles2d[tile];
          for (std::uint32_t m = 0; m < square.instance_count; ++m) {
            const gpu::MoleculeInstance& inst = s.instances[square.first_instance + m];
            const double u = a * s_uv + inst.position.x / kK, v = b * s_uv + inst.position.y / kK;
            if (!(u > 0 && u <= 2 && v >= 0 && v < 2)) continue;
            const dvec3 origin(mirrored ? kL - kK * u : kK * u, kK * v, inst.position.z);
            const glm::dmat3 frame = mirrored ? glm::dmat3(-1, 0, 0, 0, -1, 0, 0, 0, 1) : glm::dmat3(1.0);
            add_copy({ci, 0, {a, b, 0}, m, 0}, world, origin, frame * rotation_of(inst.rotation), inst);
          }
        }
    } else {
      for (int k = 0; k < kGridDims.z; ++k)
        for (int j = 0; j < kGridDims.y; ++j)
          for (int i = 0; i < kGridDims.x; ++i) {
            const int box = i + kGridDims.x * (j + kGridDims.y * k);
            if (kOccupancy[box] == O) continue;
            const gpu::Tile3D& cube = s.tiles3d[i % 2 == 0 ? 1 : 2];  // recipe [1, 2] along x, wrapping
            for (std::uint32_t m = 0; m < cube.instance_count; ++m) {
              if (kOccupancy[box] == B && !((kKeep.at(box) >> m) & 1u)) continue;
              const gpu::MoleculeInstance& inst = s.instances[cube.first_instance + m];
              const dvec3 origin = dvec3(kGridMin) + kBox * dvec3(i, j, k) + dvec3(inst.position);
              add_copy({ci, 1, {i, j, k}, m, 0}, world, origin, rotation_of(inst.rotation), inst);
            }
          }
    }
  }
  return out;
}

}  // namespace nano::explicit_test
