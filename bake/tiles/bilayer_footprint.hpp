#pragma once
// How much of a bilayer a membrane protein takes: the area of one leaflet its atoms occupy, as a
// membrane builder counts the lipids a protein displaces (the union of the atoms' cross-sections
// with the leaflet's slab, projected on the membrane plane).
#include "bake/tiles/molecule_type.hpp"

namespace nano::tiles {

// Half of a bilayer along tile-space z (the normal): [z_low, z_high], Å.
struct LeafletSlab {
  float z_low = 0.f, z_high = 0.f;
};

// The lipid slabs of a bilayer whose leaflets reach `half_thickness` Å from the mid-plane z = 0.
inline LeafletSlab outer_leaflet(float half_thickness) { return {0.f, half_thickness}; }
inline LeafletSlab inner_leaflet(float half_thickness) { return {-half_thickness, 0.f}; }

// Area (Å²) of the union of the discs where the copy's atoms meet the slab, projected along z,
// counted on a square grid of `cell` Å (error ~ perimeter · cell / 2). 0 when no atom meets it.
double leaflet_footprint(const MoleculeType& type, const Instance& copy, LeafletSlab slab, float cell = 0.25f);

}  // namespace nano::tiles
