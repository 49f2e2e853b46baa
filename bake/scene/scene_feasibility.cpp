#include "bake/scene/scene_feasibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "common/error.hpp"

namespace nano::scene {
namespace {

constexpr double kA2PerUm2 = 1e8;
constexpr double kA3PerUm3 = 1e12;
constexpr double kA2PerNm2 = 100.0;
// mM -> copies per Å³: 1e-3 mol/L · N_A / 1e27 Å³/L.
constexpr double kCopiesPerA3PerMillimolar = 1e-3 * 6.02214076e23 / 1e27;
// Random sequential addition of equal spheres jams at a volume fraction of 0.38; no placement of
// bounding spheres gets past close packing (0.74).
constexpr double kMaxSphereFraction = 0.74;

// "7.1e4", "0.0365", "1e12": three significant digits, exponents without '+' and leading zeros;
// whole numbers below 10^7 (counts) in full.
std::string short_number(double v) {
  char text[64];
  if (v == std::floor(v) && std::fabs(v) < 1e7) {
    std::snprintf(text, sizeof text, "%.0f", v);
    return text;
  }
  std::snprintf(text, sizeof text, "%.3g", v);
  std::string s = text;
  const std::size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  if (!exponent.empty() && exponent[0] == '+') exponent.erase(0, 1);
  const bool negative = !exponent.empty() && exponent[0] == '-';
  if (negative) exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// A bound printed to three significant digits on its own side: "at least" rounded up and "at most"
// rounded down, so that the value the message names passes the check it failed.
double three_digits(double v, bool up) {
  if (!(v > 0.0) || !std::isfinite(v)) return v;
  const double step = std::pow(10.0, std::floor(std::log10(v)) - 2.0);
  const double units = v / step;
  return (up ? std::ceil(units * (1.0 - 1e-12)) : std::floor(units * (1.0 + 1e-12))) * step;
}
std::string at_least(double v) { return short_number(three_digits(v, true)); }
std::string at_most(double v) { return short_number(three_digits(v, false)); }
// The same for a bound of either sign: rounded up (`up`) or down.
std::string signed_bound(double v, bool up) {
  return v < 0.0 ? "-" + short_number(three_digits(-v, !up)) : short_number(three_digits(v, up));
}

[[noreturn]] void refuse(const SceneDescription& scene, const std::string& key, const std::string& rule) {
  throw InputError(scene.source.string(), key, rule);
}

std::string membrane_key(const MembraneDescription& m) { return "membranes." + m.name; }
std::string soluble_key(const SolubleDescription& s) { return "solubles." + s.name; }

// A copies-per-Å² amount back in the scene's own unit.
std::string surface_amount_text(const MembraneDescription& m, const SurfaceAbundance& a, double copies_per_a2) {
  return a.unit == SurfaceAbundance::Unit::per_um2 ? short_number(copies_per_a2 * kA2PerUm2) + " per µm²"
                                                   : short_number(copies_per_a2 * m.tile_size * m.tile_size) + " per tile";
}

// A copies-per-Å³ amount back in the scene's own unit.
std::string volume_amount_text(const VolumeAbundance& a, double copies_per_a3) {
  return a.unit == VolumeAbundance::Unit::millimolar ? short_number(copies_per_a3 / kCopiesPerA3PerMillimolar) + " mM"
                                                     : short_number(copies_per_a3 * kA3PerUm3) + " per µm³";
}

// The least amount that places a copy, in the scene's own unit, rounded up.
std::string least_surface_amount(const MembraneDescription& m, const SurfaceAbundance& a, double copies_per_a2) {
  return a.unit == SurfaceAbundance::Unit::per_um2 ? at_least(copies_per_a2 * kA2PerUm2) + " per µm²"
                                                   : at_least(copies_per_a2 * m.tile_size * m.tile_size) + " per tile";
}
std::string least_volume_amount(const VolumeAbundance& a, double copies_per_a3) {
  return a.unit == VolumeAbundance::Unit::millimolar ? at_least(copies_per_a3 / kCopiesPerA3PerMillimolar) + " mM"
                                                     : at_least(copies_per_a3 * kA3PerUm3) + " per µm³";
}

void check_edge(const SceneDescription& scene, const std::string& key, double edge, const char* what) {
  if (edge < kMinTileSize)
    refuse(scene, key,
           short_number(edge) + " Å: a " + what + " must hold at least one molecule (a lipid is about 8 Å across); at least " +
               short_number(kMinTileSize) + " Å");
  if (edge > kMaxTileSize)
    refuse(scene, key,
           short_number(edge) + " Å: one " + what + " would hold more copies than a machine stores (a 100 µm² square of membrane is 1.5e8 lipids); at most " +
               short_number(kMaxTileSize) + " Å");
}

// The key a compartment's size comes from, and the factor by which that value must shrink.
std::string size_key(const CompartmentDescription& c) {
  const std::string mesh = "compartments." + c.name + ".mesh.";
  if (c.mesh.diameter) return mesh + "diameter";
  if (c.mesh.volume) return mesh + "volume";
  if (c.scale != 1.0) return "compartments." + c.name + ".scale";
  if (c.mesh.kind == MeshSource::Kind::sphere) return mesh + "radius";
  if (c.mesh.kind == MeshSource::Kind::file) return mesh + (c.mesh.unit != 1.0 ? "units" : "file");
  return "compartments." + c.name + ".mesh";
}
// The unit the size key's value is written in.
const char* size_unit(const CompartmentDescription& c) {
  if (c.mesh.diameter) return " Å";
  if (c.mesh.volume) return " Å³";
  if (c.scale != 1.0) return "";
  return c.mesh.kind == MeshSource::Kind::sphere ? " Å" : "";
}

double size_value(const CompartmentDescription& c) {
  if (c.mesh.diameter) return *c.mesh.diameter;
  if (c.mesh.volume) return *c.mesh.volume;
  if (c.scale != 1.0) return c.scale;
  if (c.mesh.kind == MeshSource::Kind::sphere) return c.mesh.radius;
  return 0.0;
}

[[noreturn]] void refuse_extent(const SceneDescription& scene, const CompartmentDescription& c, double extent) {
  const double shrink = kMaxCompartmentExtent / extent;
  const bool by_volume = c.mesh.volume && !c.mesh.diameter;
  const double value = size_value(c);
  std::string rule = "the mesh reaches " + short_number(extent) +
                     " Å from the compartment's origin; compartment coordinates are float32 on the GPU, coarser than "
                     "1/8 Å beyond " + short_number(kMaxCompartmentExtent) + " Å (105 µm), too coarse for atoms";
  if (value > 0.0) rule += "; at most " + short_number(value * (by_volume ? shrink * shrink * shrink : shrink)) + size_unit(c);
  refuse(scene, size_key(c), rule);
}

// A nonzero amount so small that the whole tile set holds no copy: the scene would lose the
// molecule without a word.
void check_membrane_places_some(const SceneDescription& scene, const MembraneDescription& m) {
    const double set_area = m.tiles * m.tile_size * m.tile_size;  // Å²
    for (std::size_t i = 0; i < m.proteins.size(); ++i) {
      const double expected = copies_per_a2(m, m.proteins[i].abundance) * set_area;
      if (m.proteins[i].abundance.value > 0.0 && expected < 1.0)
        refuse(scene, amount_key(m, i),
               short_number(m.proteins[i].abundance.value) + " places no copy: the " + std::to_string(m.tiles) +
                   " tiles of " + short_number(m.tile_size) + " Å hold " + short_number(set_area / kA2PerUm2) +
                   " µm² of membrane, so at least " + surface_amount_text(m, m.proteins[i].abundance, 1.0 / set_area) +
                   " (or 0 for none)");
      // A count of 0 drops every copy the tiles place, on every compartment.
      if (m.proteins[i].abundance.value > 0.0 && m.proteins[i].per_compartment && *m.proteins[i].per_compartment == 0) {
        const std::string amount = amount_key(m, i);
        const std::string unit = amount.substr(amount.rfind('.') + 1);
        refuse(scene, protein_key(m, i, "per_compartment"),
               "0 keeps no copy of '" + m.proteins[i].molecule.name + "' on any compartment, though its " + unit +
                   " asks for " + short_number(m.proteins[i].abundance.value) + "; at least 1 (or " + unit +
                   " 0 for none)");
      }
    }
    // A lipid fill stands one lipid per area_per_lipid in each leaflet.
    if (m.lipids && set_area / m.lipids->area_per_lipid < 1.0)
      refuse(scene, membrane_key(m) + ".lipids.area_per_lipid",
             short_number(m.lipids->area_per_lipid) + " Å² places no lipid: the " + std::to_string(m.tiles) + " tiles of " +
                 short_number(m.tile_size) + " Å hold " + short_number(set_area) +
                 " Å² of each leaflet, so at most " + at_most(set_area) + " Å² per lipid (a real bilayer: 55-75 Å²)");
}

void check_soluble_places_some(const SceneDescription& scene, const SolubleDescription& s) {
    const double set_volume = s.cubes * s.cube_size * s.cube_size * s.cube_size;  // Å³
    for (std::size_t i = 0; i < s.molecules.size(); ++i) {
      const double expected = copies_per_a3(s.molecules[i].abundance) * set_volume;
      if (s.molecules[i].abundance.value > 0.0 && expected < 1.0)
        refuse(scene, amount_key(s, i),
               short_number(s.molecules[i].abundance.value) + " places no copy: the " + std::to_string(s.cubes) +
                   " cubes of " + short_number(s.cube_size) + " Å hold " + short_number(set_volume / kA3PerUm3) +
                   " µm³, so at least " + volume_amount_text(s.molecules[i].abundance, 1.0 / set_volume) +
                   " (or 0 for none; more or larger cubes hold rarer molecules)");
    }
}

std::string too_many_triangles(double triangles) {
  return short_number(triangles) + " triangles: a proxy mesh is low-poly (the membrane's remeshing makes at most 4e5), "
         "and its shells and UV charts grow with every triangle; at most " + short_number(kMaxMeshTriangles);
}

}  // namespace

double copies_per_a2(const MembraneDescription& m, const SurfaceAbundance& a) {
  return a.unit == SurfaceAbundance::Unit::per_um2 ? a.value / kA2PerUm2 : a.value / (m.tile_size * m.tile_size);
}

double copies_per_a3(const VolumeAbundance& a) {
  return a.unit == VolumeAbundance::Unit::millimolar ? a.value * kCopiesPerA3PerMillimolar : a.value / kA3PerUm3;
}

std::string protein_key(const MembraneDescription& m, std::size_t i, const std::string& field) {
  return membrane_key(m) + ".proteins[" + std::to_string(i) + "]." + field;
}

std::string amount_key(const MembraneDescription& m, std::size_t i) {
  return protein_key(m, i, m.proteins.at(i).abundance.unit == SurfaceAbundance::Unit::per_um2 ? "density_per_um2" : "copies_per_tile");
}

std::string amount_key(const SolubleDescription& s, std::size_t i) {
  return soluble_key(s) + ".molecules[" + std::to_string(i) + "]." +
         (s.molecules.at(i).abundance.unit == VolumeAbundance::Unit::millimolar ? "concentration_mM" : "copies_per_um3");
}

void check_scene_amounts(const SceneDescription& scene) {
  for (const MembraneDescription& m : scene.membranes) check_edge(scene, membrane_key(m) + ".tile_size", m.tile_size, "Wang square");
  for (const SolubleDescription& s : scene.solubles) check_edge(scene, soluble_key(s) + ".cube_size", s.cube_size, "Wang cube");
  // Sizes known before the mesh is read: a generated sphere's radius, a target diameter or volume.
  for (const CompartmentDescription& c : scene.compartments) {
    double reach = 0.0;  // a lower bound on how far the mesh reaches from its origin
    if (c.mesh.diameter) reach = 0.5 * *c.mesh.diameter;
    else if (c.mesh.volume) reach = std::cbrt(*c.mesh.volume * 3.0 / (4.0 * std::numbers::pi));
    else if (c.mesh.kind == MeshSource::Kind::sphere) reach = c.mesh.radius * c.scale;
    else if (c.mesh.kind == MeshSource::Kind::box) reach = 0.5 * glm::length(c.mesh.box_size) * c.scale;
    if (reach > kMaxCompartmentExtent) refuse_extent(scene, c, reach);
    if (c.mesh.kind != MeshSource::Kind::file && c.mesh.triangles > kMaxMeshTriangles)
      refuse(scene, "compartments." + c.name + ".mesh.triangles", too_many_triangles(c.mesh.triangles));
  }
}

namespace {

// An outer-leaflet lipid stands at +offset along the normal (the inner one mirrored at −offset), so
// its tail end is offset − reach_below from the mid-surface: the leaflets meet where that is ~0.
void check_leaflets_meet(const SceneDescription& scene, const MembraneDescription& m, const MoleculeMeasure& l) {
  const double tail_end = m.lipids->leaflet_offset - l.reach_below;
  if (std::abs(tail_end) <= kLeafletMeetTolerance) return;
  const std::string apart = tail_end > 0.0 ? "leaves lipid '" + m.lipids->molecule.name +
                                                 "' detached from its membrane: the two leaflets stand " +
                                                 short_number(2.0 * tail_end) + " Å apart, with nothing between them"
                                           : "runs the tails of lipid '" + m.lipids->molecule.name +
                                                 "' through the other leaflet: the leaflets overlap by " +
                                                 short_number(-2.0 * tail_end) + " Å";
  refuse(scene, membrane_key(m) + ".lipids.leaflet_offset",
         short_number(m.lipids->leaflet_offset) + " Å " + apart + " (its tail end reaches " +
             short_number(l.reach_below) + " Å below its centre, and a bilayer's leaflets meet at the mid-surface); " +
             (tail_end > 0.0 ? "at most " + at_most(l.reach_below + kLeafletMeetTolerance)
                             : "at least " + at_least(std::max(0.0, l.reach_below - kLeafletMeetTolerance))) +
             " Å");
}

// Each protein and the lipid fit a tile, and the lipid's area is no smaller than its own cross-section.
void check_membrane_sizes(const SceneDescription& scene, const MembraneDescription& m,
                          std::span<const MoleculeMeasure> molecules) {
  const std::string key = membrane_key(m);
  for (std::size_t i = 0; i < m.proteins.size(); ++i) {
    const MoleculeMeasure& p = molecules[m.proteins[i].molecule.index];
    if (2.0 * p.lateral_radius > m.tile_size)
      refuse(scene, key + ".tile_size",
             short_number(m.tile_size) + " Å: '" + m.proteins[i].molecule.name + "' spans " +
                 short_number(2.0 * p.lateral_radius) + " Å across the membrane, more than a tile; at least " +
                 short_number(2.0 * p.lateral_radius) + " Å");
  }
  check_membrane_places_some(scene, m);
  if (!m.lipids) return;
  const MoleculeMeasure& l = molecules[m.lipids->molecule.index];
  if (2.0 * l.lateral_radius > m.tile_size)
    refuse(scene, key + ".tile_size",
           short_number(m.tile_size) + " Å: lipid '" + m.lipids->molecule.name + "' spans " +
               short_number(2.0 * l.lateral_radius) + " Å, more than a tile; at least " +
               short_number(2.0 * l.lateral_radius) + " Å");
  // Copies standing side by side in one leaflet fill a slab as thick as one of them is long.
  const double least = l.height > 0.0 ? l.volume / l.height : 0.0;
  if (m.lipids->area_per_lipid < least)
    refuse(scene, key + ".lipids.area_per_lipid",
           short_number(m.lipids->area_per_lipid) + " Å² cannot fit: lipid '" + m.lipids->molecule.name + "' takes " +
               short_number(l.volume) + " Å³ over its " + short_number(l.height) +
               " Å length, so at least " + short_number(least) + " Å² per lipid (a real bilayer: 55-75 Å²)");
  check_leaflets_meet(scene, m, l);
}

// Proteins share each leaflet: their footprints add up to at most the whole leaflet.
void check_leaflet_coverage(const SceneDescription& scene, const MembraneDescription& m,
                            std::span<const MoleculeMeasure> molecules) {
  double outer = 0.0, inner = 0.0;  // leaflet fractions covered so far
  for (std::size_t i = 0; i < m.proteins.size(); ++i) {
    const MembraneProtein& protein = m.proteins[i];
    const MoleculeMeasure& p = molecules[protein.molecule.index];
    const double d = copies_per_a2(m, protein.abundance);
    const double covered_outer = outer + d * p.outer_footprint, covered_inner = inner + d * p.inner_footprint;
    const double layer = p.height > 0.0 ? d * p.volume / p.height : 0.0;  // its own slab, alone
    const bool over_leaflet = covered_outer > kMaxLeafletCoverage || covered_inner > kMaxLeafletCoverage;
    if (over_leaflet || layer > kMaxLeafletCoverage) {
      const double footprint = std::max(p.outer_footprint, p.inner_footprint);
      const double before = p.outer_footprint >= p.inner_footprint ? outer : inner;
      double most = over_leaflet ? (kMaxLeafletCoverage - before) / footprint : kMaxLeafletCoverage * p.height / p.volume;
      if (over_leaflet && p.height > 0.0) most = std::min(most, kMaxLeafletCoverage * p.height / p.volume);
      most = std::max(most, 0.0);
      std::string rule = short_number(protein.abundance.value) + " cannot fit: '" + protein.molecule.name + "' ";
      if (over_leaflet)
        rule += "covers " + short_number(footprint / kA2PerNm2) + " nm² of a leaflet";
      else
        rule += "takes " + short_number(p.volume / p.height / kA2PerNm2) + " nm² of its layer on average";
      rule += ", at most " + surface_amount_text(m, protein.abundance, most);
      if (over_leaflet && before > 0.0)
        rule += " beside the proteins listed before it (they cover " + short_number(100.0 * before) + "% of the leaflet)";
      refuse(scene, amount_key(m, i), rule);
    }
    outer = covered_outer;
    inner = covered_inner;
  }
}

// Each soluble fits a cube, and together they fill at most close-packed spheres' share of the volume.
void check_soluble_amounts(const SceneDescription& scene, const SolubleDescription& s,
                           std::span<const MoleculeMeasure> molecules) {
  for (const SolubleMolecule& molecule : s.molecules) {
    const MoleculeMeasure& mm = molecules[molecule.molecule.index];
    if (2.0 * mm.bounding_radius > s.cube_size)
      refuse(scene, soluble_key(s) + ".cube_size",
             short_number(s.cube_size) + " Å: '" + molecule.molecule.name + "' spans " +
                 short_number(2.0 * mm.bounding_radius) + " Å, more than a cube; at least " +
                 short_number(2.0 * mm.bounding_radius) + " Å");
  }
  check_soluble_places_some(scene, s);
  double filled = 0.0;  // volume fraction of the cubes taken so far
  for (std::size_t i = 0; i < s.molecules.size(); ++i) {
    const SolubleMolecule& molecule = s.molecules[i];
    const MoleculeMeasure& mm = molecules[molecule.molecule.index];
    const double fraction = copies_per_a3(molecule.abundance) * mm.volume;
    if (filled + fraction > kMaxSolubleVolumeFraction) {
      const double most = std::max(0.0, (kMaxSolubleVolumeFraction - filled) / mm.volume);
      std::string rule = short_number(molecule.abundance.value) + " cannot fit: '" + molecule.molecule.name + "' takes " +
                         short_number(mm.volume) + " Å³ a copy, which would fill " + short_number(100.0 * fraction) +
                         "% of the volume; at most " + volume_amount_text(molecule.abundance, most);
      if (filled > 0.0)
        rule += " beside the molecules listed before it (they fill " + short_number(100.0 * filled) + "%)";
      rule += " (atoms fill at most " + short_number(100.0 * kMaxSolubleVolumeFraction) + "% of space, as close-packed spheres)";
      refuse(scene, amount_key(s, i), rule);
    }
    filled += fraction;
  }
}

}  // namespace

void check_molecule_amounts(const SceneDescription& scene, std::span<const MoleculeMeasure> molecules) {
  // Invariant, not input: the baker measures every molecule of the scene (so below).
  if (molecules.size() != scene.molecules.size())
    throw std::invalid_argument("check_molecule_amounts: one measure per molecule is needed");
  for (const MembraneDescription& m : scene.membranes) {
    check_membrane_sizes(scene, m, molecules);
    check_leaflet_coverage(scene, m, molecules);
  }
  for (const SolubleDescription& s : scene.solubles) check_soluble_amounts(scene, s, molecules);
}

namespace {

const MoleculeMeasure& measure_of(std::span<const MoleculeMeasure> molecules, const NameRef& molecule, const char* check) {
  if (molecule.index >= molecules.size())  // invariant: the parser resolved the name to a molecule of the scene
    throw std::invalid_argument(std::string(check) + ": one measure per molecule is needed");
  return molecules[molecule.index];
}

// "from -56.4 to 54.1 Å" (more digits where three would print both ends alike)
std::string range_text(double lo, double hi) {
  if (short_number(lo) != short_number(hi)) return "from " + short_number(lo) + " to " + short_number(hi) + " Å";
  char text[80];
  std::snprintf(text, sizeof text, "from %.9g to %.9g Å", lo, hi);
  return text;
}

// A membrane protein is laid along the surface's normal with its centre at its depth: standing clear
// of the bilayer's slab, its copies hang where no ray meets them beside the compartment they belong
// to. (A lipid fill makes the slab itself; check_leaflets_meet judges its offset.)
void check_bilayer_reach(const SceneDescription& scene, const CompartmentDescription& c, const MembraneDescription& m,
                         double thickness, std::span<const MoleculeMeasure> molecules) {
  const double half = 0.5 * thickness;
  const std::string slab = "the " + short_number(thickness) + " Å thick bilayer of compartment '" + c.name + "' (" +
                           range_text(-half, half) + " about its mid-surface)";
  for (std::size_t i = 0; i < m.proteins.size(); ++i) {
    const MembraneProtein& protein = m.proteins[i];
    if (!(protein.abundance.value > 0.0)) continue;
    const MoleculeMeasure& p = measure_of(molecules, protein.molecule, "check_compartment_amounts");
    const double lo = protein.depth - p.reach_below, hi = protein.depth + p.reach_above;
    if (hi >= -half && lo <= half) continue;
    refuse(scene, protein_key(m, i, "depth"),
           short_number(protein.depth) + " Å leaves '" + protein.molecule.name +
               "' detached from its membrane: standing along its up axis at that depth its atoms span " +
               range_text(lo, hi) + " from the mid-surface, clear of " + slab +
               ", so its copies would hang where no picture of the compartment shows them; a depth from " +
               signed_bound(-half - p.reach_above, true) + " to " + signed_bound(half + p.reach_below, false) + " Å");
  }
}

}  // namespace

void check_compartment_amounts(const SceneDescription& scene, std::size_t compartment, const CompartmentMeasure& mesh,
                               std::span<const MoleculeMeasure> molecules) {
  const CompartmentDescription& c = scene.compartments.at(compartment);
  if (!(mesh.extent <= kMaxCompartmentExtent)) refuse_extent(scene, c, mesh.extent);
  if (static_cast<double>(mesh.triangles) > kMaxMeshTriangles)
    refuse(scene, "compartments." + c.name + ".mesh.file", too_many_triangles(static_cast<double>(mesh.triangles)));
  if (!c.membrane) return;
  // The exact test of where a bilayer fits comes later (bake/mesh/membrane_fit.hpp), on the
  // triangles; a mesh smaller than the bilayer's own thickness fails it by its size alone.
  if (mesh.extent < mesh.bilayer_thickness) {
    const double value = size_value(c);
    std::string rule = "the mesh reaches only " + short_number(mesh.extent) + " Å from its origin, less than the " +
                       short_number(mesh.bilayer_thickness) + " Å thick bilayer it wears";
    if (value > 0.0) {
      const double grow = mesh.bilayer_thickness / std::max(mesh.extent, 1e-300);
      rule += "; at least " + short_number(value * (c.mesh.volume && !c.mesh.diameter ? grow * grow * grow : grow)) + size_unit(c);
    }
    refuse(scene, size_key(c), rule);
  }
  const MembraneDescription& m = scene.membranes.at(c.membrane->index);
  check_bilayer_reach(scene, c, m, mesh.bilayer_thickness, molecules);
  double covered = 0.0;  // Å² of the busier leaflet taken by per-compartment copies so far
  for (std::size_t i = 0; i < m.proteins.size(); ++i) {
    const MembraneProtein& protein = m.proteins[i];
    if (!protein.per_compartment) continue;
    if (protein.molecule.index >= molecules.size())  // invariant, as in measure_of
      throw std::invalid_argument("check_compartment_amounts: one measure per molecule is needed");
    const MoleculeMeasure& p = molecules[protein.molecule.index];
    const double footprint = std::max({p.outer_footprint, p.inner_footprint, p.height > 0.0 ? p.volume / p.height : 0.0});
    const double need = static_cast<double>(*protein.per_compartment) * footprint;
    if (covered + need > kMaxLeafletCoverage * mesh.area) {
      const double most = std::max(0.0, std::floor((kMaxLeafletCoverage * mesh.area - covered) / footprint));
      refuse(scene, protein_key(m, i, "per_compartment"),
             std::to_string(*protein.per_compartment) + " cannot fit on compartment '" + c.name + "': its surface is " +
                 short_number(mesh.area / kA2PerUm2) + " µm² and '" + protein.molecule.name + "' covers " +
                 short_number(footprint / kA2PerNm2) + " nm²; at most " + short_number(most));
    }
    covered += need;
  }
}

namespace {

// A soluble copy is kept only where its centre is inside the mesh and its bounding sphere stays the
// clearance (and the membrane shell's inner reach) away from the surface: no point inside lies
// deeper than mesh.deepest, so the largest listed molecule bounds the room.
void check_soluble_room(const SceneDescription& scene, const CompartmentDescription& c, const SolubleDescription& s,
                        const CompartmentMeasure& mesh, std::span<const MoleculeMeasure> molecules) {
  const SolubleMolecule* largest = nullptr;
  double radius = 0.0;
  for (const SolubleMolecule& molecule : s.molecules) {
    if (!(molecule.abundance.value > 0.0)) continue;
    const double r = measure_of(molecules, molecule.molecule, "check_compartment_room").bounding_radius;
    if (!largest || r > radius) {
      largest = &molecule;
      radius = r;
    }
  }
  if (!largest || !(mesh.deepest > 0.0)) return;
  const std::string depth = "no point inside the mesh of compartment '" + c.name + "' is farther than " +
                            short_number(mesh.deepest) + " Å from its surface";
  const std::string shell = c.membrane ? " (and its membrane shell's inner reach)" : "";
  if (radius > mesh.deepest) {
    const double value = size_value(c);
    std::string rule = depth + ", and soluble '" + largest->molecule.name + "' reaches " + short_number(radius) +
                       " Å from its centre: no copy fits inside";
    if (value > 0.0) {
      const double grow = (radius + s.clearance) / mesh.deepest;
      rule += "; at least " + at_least(value * (c.mesh.volume && !c.mesh.diameter ? grow * grow * grow : grow)) + size_unit(c);
    }
    refuse(scene, size_key(c), rule);
  }
  if (radius + s.clearance > mesh.deepest)
    refuse(scene, soluble_key(s) + ".clearance",
           short_number(s.clearance) + " Å leaves no room for solubles: " + depth + ", and a copy of '" +
               largest->molecule.name + "' is kept only where its " + short_number(radius) +
               " Å bounding sphere stays the clearance" + shell + " away from it; at most " +
               at_most(mesh.deepest - radius) + " Å");
}

}  // namespace

void check_compartment_room(const SceneDescription& scene, std::size_t compartment, const CompartmentMeasure& mesh,
                            std::span<const MoleculeMeasure> molecules) {
  const CompartmentDescription& c = scene.compartments.at(compartment);
  if (c.membrane) {
    // The tiles place their density over the whole surface: a compartment smaller than one copy's
    // share of membrane most likely holds none.
    const MembraneDescription& m = scene.membranes.at(c.membrane->index);
    const std::string surface = " on compartment '" + c.name + "': its " + short_number(mesh.area / kA2PerUm2) +
                                " µm² of membrane hold ";
    for (std::size_t i = 0; i < m.proteins.size(); ++i) {
      const SurfaceAbundance& amount = m.proteins[i].abundance;
      const double expected = copies_per_a2(m, amount) * mesh.area;
      if (amount.value > 0.0 && expected < 1.0)
        refuse(scene, amount_key(m, i),
               short_number(amount.value) + " places no copy" + surface + short_number(expected) + " of '" +
                   m.proteins[i].molecule.name + "' at that density, so at least " +
                   least_surface_amount(m, amount, 1.0 / mesh.area) +
                   " (or 0 for none)");
    }
    if (m.lipids && mesh.area / m.lipids->area_per_lipid < 1.0)
      refuse(scene, membrane_key(m) + ".lipids.area_per_lipid",
             short_number(m.lipids->area_per_lipid) + " Å² places no lipid" + surface + short_number(mesh.area) +
                 " Å² of each leaflet; at most " + at_most(mesh.area) + " Å² per lipid (a real bilayer: 55-75 Å²)");
  }
  if (!c.soluble) return;
  const SolubleDescription& s = scene.solubles.at(c.soluble->index);
  check_soluble_room(scene, c, s, mesh, molecules);
  for (std::size_t i = 0; i < s.molecules.size(); ++i) {
    const VolumeAbundance& amount = s.molecules[i].abundance;
    const double expected = copies_per_a3(amount) * mesh.volume;
    if (amount.value > 0.0 && expected < 1.0)
      refuse(scene, amount_key(s, i),
             short_number(amount.value) + " places no copy in compartment '" + c.name + "': its " +
                 short_number(mesh.volume / kA3PerUm3) + " µm³ hold " + short_number(expected) + " of '" +
                 s.molecules[i].molecule.name + "' at that concentration, so at least " +
                 least_volume_amount(amount, 1.0 / mesh.volume) + " (or 0 for none)");
  }
}

void check_lipid_mix_amounts(const SceneDescription& scene, std::size_t membrane, const PatchPlaces& places) {
  const MembraneDescription& m = scene.membranes.at(membrane);
  for (std::size_t j = 0; j < m.lipid_mix.size(); ++j) {
    const LipidPatchDescription& species = m.lipid_mix[j];
    for (const bool outer : {true, false}) {
      const double fraction = outer ? species.outer : species.inner;
      const double n = outer ? places.outer : places.inner;
      if (!(fraction > 0.0) || fraction * n >= 0.5) continue;  // lround(fraction x places) > 0
      const char* leaflet = outer ? "outer" : "inner";
      std::string rule = short_number(fraction) + " places no lipid of '" + species.name + "': ";
      if (n < 1.0)
        rule += std::string("the patch has no lipid in the ") + leaflet + " leaflet; 0";
      else
        rule += "a tile of the patch has at most " + short_number(n) + " places in the " + leaflet +
                " leaflet, and that share of them rounds to none; at least " + at_least(0.5 / n) + " (or 0 for none)";
      refuse(scene, membrane_key(m) + ".lipid_mix[" + std::to_string(j) + "]." + leaflet, rule);
    }
  }
}

namespace {

std::uint64_t count_of(const LeafletCounts& counts, const std::string& kind) {
  for (const auto& [name, n] : counts)
    if (name == kind) return n;
  return 0;
}

std::string counts_text(const LeafletCounts& counts, std::uint64_t total) {
  std::string text;
  for (const auto& [name, n] : counts)
    text += (text.empty() ? "" : ", ") + name + " " + short_number(n) + " (" +
            short_number(std::round(1000.0 * static_cast<double>(n) / static_cast<double>(total)) / 10.0) + " %)";
  return text;
}

void check_one_leaflet(const SceneDescription& scene, const MembraneDescription& m, const LeafletComposition& asked,
                       const LeafletCounts& counts, const char* leaflet, std::string_view whose) {
  std::uint64_t total = 0;
  for (const auto& [name, n] : counts) total += n;
  const std::string key = membrane_key(m) + ".lipid_patch.leaflets." + leaflet + ".mol_percent";
  // A kind the leaflet holds but the scene does not list is asked 0 %.
  std::vector<std::pair<std::string, double>> shares = asked.mol_percent;
  for (const auto& held : counts)  // not a structured binding: clang 14 (the fuzz build) cannot capture one
    if (std::none_of(shares.begin(), shares.end(), [&](const auto& a) { return a.first == held.first; }))
      shares.emplace_back(held.first, 0.0);
  for (const auto& [kind, percent] : shares) {
    const std::uint64_t n = count_of(counts, kind);
    const double share = total > 0 ? 100.0 * static_cast<double>(n) / static_cast<double>(total) : 0.0;
    if (percent > 0.0 && n == 0)
      refuse(scene, key + "." + kind,
             short_number(percent) + " % of the " + leaflet + " leaflet asked, but " + std::string(whose) + " no " + kind +
                 " there (" + (total > 0 ? counts_text(counts, total) : "no lipid") + ")");
    if (std::abs(share - percent) > kLeafletShareTolerance)
      refuse(scene, key + "." + kind,
             short_number(percent) + " % of the " + leaflet + " leaflet asked, but " + std::string(whose) + " " +
                 short_number(std::round(share * 10.0) / 10.0) + " % (" + counts_text(counts, total) +
                 "): more than " + short_number(kLeafletShareTolerance) + " points apart");
  }
}

}  // namespace

void check_leaflet_shares(const SceneDescription& scene, std::size_t membrane, const LeafletCounts& outer,
                          const LeafletCounts& inner, std::string_view whose) {
  const MembraneDescription& m = scene.membranes.at(membrane);
  if (!m.lipid_patch || !m.lipid_patch->outer_leaflet || !m.lipid_patch->inner_leaflet) return;
  check_one_leaflet(scene, m, *m.lipid_patch->outer_leaflet, outer, "outer", whose);
  check_one_leaflet(scene, m, *m.lipid_patch->inner_leaflet, inner, "inner", whose);
}

void check_placement_amounts(const SceneDescription& scene, std::span<const double> bounding_radii) {
  if (bounding_radii.size() != scene.compartments.size())  // invariant: the baker measures every compartment
    throw std::invalid_argument("check_placement_amounts: one bounding radius per compartment is needed");
  for (std::size_t e = 0; e < scene.instances.size(); ++e) {
    const auto* placement = std::get_if<RandomPlacement>(&scene.instances[e]);
    if (!placement) continue;
    const double r = bounding_radii[placement->compartment.index] + 0.5 * placement->min_gap;
    const glm::dvec3 size = placement->box.max - placement->box.min + placement->min_gap;
    const double room = kMaxSphereFraction * size.x * size.y * size.z;
    const double one = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    if (static_cast<double>(placement->count) * one > room)
      refuse(scene, "instances[" + std::to_string(e) + "].count",
             std::to_string(placement->count) + " copies of compartment '" + placement->compartment.name +
                 "' cannot fit in the box: each needs a sphere of radius " + short_number(r) +
                 " Å (bounding sphere and half the min_gap), and spheres fill at most 74% of a box; at most " +
                 short_number(std::floor(room / one)) + " (or a larger box)");
  }
}

}  // namespace nano::scene
