#pragma once
// A generated Wang set: the tiles (squares or cubes) with their side colours and molecule copies.
#include "bake/tiles/molecule_type.hpp"
#include "bake/tiles/wang_colouring.hpp"

#include <string>
#include <vector>

namespace nano::tiles {

struct WangTile {
  SideColours colours{};
  std::vector<Instance> instances;  // each copy owned by the tile holding its centre (half-open)
  // Tile-space box of every atom of the tile's copies: straddling copies stick out of [0, edge).
  glm::vec3 atoms_min{0.f}, atoms_max{0.f};
};

struct MoleculeDensity {
  std::string name;
  uint32_t type = 0;
  double requested = 0.0;  // copies per µm² (squares) or per µm³ (cubes)
  double achieved = 0.0;   // same unit, in a tiling using every tile and colour equally often
  size_t copies_in_set = 0;
};

struct WangSet {
  int dims = 2;
  float edge = 0.f;  // Å
  WangColouring colouring;
  std::vector<WangTile> tiles;
  std::vector<MoleculeDensity> densities;

  // Largest distance any atom reaches outside [0, edge) along a lattice axis (Å, >= 0); z of a
  // square set is the membrane normal and is not a lattice axis.
  float max_overhang() const;
};

}  // namespace nano::tiles
