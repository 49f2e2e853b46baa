#include "bake/scene_bake/bake_invariants.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "bake/grid/core_grid.hpp"
#include "bake/mesh/number_text.hpp"
#include "bake/scene_bake/wang_bake.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {

double deepest_inside(const mesh::ProxyMesh& mesh, double enclosed_volume) {
  if (mesh.triangles.empty()) return 0.0;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const mesh::Triangle& t : mesh.triangles)
    for (const std::uint32_t v : t) {
      lo = glm::min(lo, mesh.positions.at(v));
      hi = glm::max(hi, mesh.positions.at(v));
    }
  double deepest = 0.5 * std::min({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  if (enclosed_volume > 0.0) deepest = std::min(deepest, std::cbrt(3.0 * enclosed_volume / (4.0 * std::numbers::pi)));
  return deepest;
}

scene::PatchPlaces patch_places(const BakedLipidPatch& patch, double tile_size) {
  // As repeat_patch (bake/tiles/wang_sets.cpp) counts its repeats: in float, rounded.
  const float edge = static_cast<float>(tile_size);
  const auto repeats = [&](double period) {
    return std::max(1L, std::lround(edge / static_cast<float>(period)));
  };
  const double cells = static_cast<double>(repeats(patch.period_x)) * static_cast<double>(repeats(patch.period_y));
  scene::PatchPlaces places;
  for (const glm::dvec3& p : patch.positions) (static_cast<float>(p.z) >= 0.f ? places.outer : places.inner) += cells;
  return places;
}

void check_nothing_emptied(const scene::SceneDescription& scene, std::span<const scene::MoleculeMeasure> molecules,
                           const std::vector<std::optional<BakedLipidPatch>>& patches,
                           std::span<const scene::CompartmentMeasure> meshes,
                           const std::function<const mesh::ProxyMesh&(std::size_t)>& mesh_of) {
  if (meshes.size() != scene.compartments.size())  // invariant: the baker measures every compartment
    throw std::invalid_argument("check_nothing_emptied: one mesh measure per compartment is needed");
  for (std::size_t m = 0; m < scene.membranes.size() && m < patches.size(); ++m)
    if (patches[m]) scene::check_lipid_mix_amounts(scene, m, patch_places(*patches[m], scene.membranes[m].tile_size));
  for (std::size_t c = 0; c < scene.compartments.size(); ++c) {
    scene::CompartmentMeasure measure = meshes[c];
    if (scene.compartments[c].soluble) measure.deepest = deepest_inside(mesh_of(c), measure.volume);
    scene::check_compartment_room(scene, c, measure, molecules);
    if (scene.compartments[c].soluble) {
      // The core grid the bake will lay (core_bake.cpp), sized now: its recipe must be one it can build.
      const scene::SolubleDescription& s = scene.solubles.at(scene.compartments[c].soluble->index);
      const grid::CoreGrid grid = grid::make_core_grid(mesh_of(c), s.cube_size, {}, "soluble '" + s.name + "'");
      check_recipe_covers(complete_cube_set(s), {grid.dims.x, grid.dims.y, grid.dims.z}, s.name, &s);
    }
  }
}

namespace {

using NamedCounts = std::vector<std::pair<std::string, std::uint64_t>>;

std::uint64_t count_of(const NamedCounts& list, const std::string& name) {
  const auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == name; });
  return it == list.end() ? 0 : it->second;
}

std::string number(double v) { return mesh::number_text("%.3g", v); }

// What the Wang set (`set`, by index into baked.wang_sets) holds of `name`, when it says.
const tiles::MoleculeDensity* in_set(const BakedScene& baked, std::size_t set, const std::string& name) {
  if (set >= baked.wang_sets.size()) return nullptr;
  const auto& densities = baked.wang_sets[set].densities;
  const auto it = std::find_if(densities.begin(), densities.end(), [&](const auto& d) { return d.name == name; });
  return it == densities.end() ? nullptr : &*it;
}

std::string empty_set(const tiles::MoleculeDensity& d, const char* set, const char* unit) {
  return std::string("the ") + set + " holds no copy of it (the packer reached " + number(d.achieved) + " of the " +
         number(d.requested) + unit + " asked)";
}

// Why a membrane molecule has no copy on a compartment's surface.
std::string membrane_reason(const BakedScene& baked, std::size_t set, const CompartmentSummary& c, const std::string& name) {
  if (const tiles::MoleculeDensity* d = in_set(baked, set, name); d && d->copies_in_set == 0)
    return empty_set(*d, "tile set", " per µm²");
  if (c.membrane) {
    const std::uint64_t dropped = count_of(c.membrane->dropped, name), unfit = count_of(c.membrane->unfit, name);
    if (dropped > 0) {
      std::string why = "no copy survived: all " + std::to_string(dropped) + " the tiles put on its surface were dropped (";
      if (unfit > 0) why += std::to_string(unfit) + " where no prism fits";
      if (unfit > 0 && dropped > unfit) why += ", ";
      if (dropped > unfit) why += std::to_string(dropped - unfit) + " clashing on the surface or beyond per_compartment";
      return why + ")";
    }
    return "the tiles put no copy on its " + number(c.membrane->area_um2) + " µm² of membrane";
  }
  return "the tiles put no copy on its membrane";
}

// Why a soluble has no copy inside a compartment.
std::string soluble_reason(const BakedScene& baked, std::size_t set, const CompartmentSummary& c,
                           const scene::SolubleDescription& s, const std::string& name) {
  if (const tiles::MoleculeDensity* d = in_set(baked, set, name); d && d->copies_in_set == 0)
    return empty_set(*d, "cube set", " per µm³");
  if (c.core_boxes_inside + c.core_boxes_boundary == 0) return "its core grid has no box inside the mesh";
  return "no copy survived: its core grid has " + std::to_string(c.core_boxes_inside) + " boxes wholly inside the mesh and " +
         std::to_string(c.core_boxes_boundary) + " along its surface, and no copy in them stands inside with its bounding "
         "sphere the clearance (" + number(s.clearance) + " Å)" + (c.membrane ? " and the membrane shell's inner reach" : "") +
         " away from the surface";
}

}  // namespace

void check_every_molecule_placed(const scene::SceneDescription& scene, const BakedScene& baked) {
  if (baked.compartments.size() != scene.compartments.size())  // invariant: the baker bakes every compartment
    throw std::invalid_argument("check_every_molecule_placed: one summary per compartment is needed");
  const auto refuse = [&](const std::string& key, const std::string& amount, const CompartmentSummary& c,
                          const std::string& name, const std::string& why) {
    throw InputError(scene.source.string(), key,
                     amount + " gives compartment '" + c.name + "' no copy of '" + name + "': " + why);
  };
  for (std::size_t ci = 0; ci < scene.compartments.size(); ++ci) {
    const scene::CompartmentDescription& description = scene.compartments[ci];
    const CompartmentSummary& c = baked.compartments[ci];
    const auto placed = [&](const std::string& name) { return count_of(c.copies, name) > 0; };
    if (description.membrane) {
      const std::size_t mi = description.membrane->index;
      const scene::MembraneDescription& m = scene.membranes.at(mi);
      const std::string key = "membranes." + m.name;
      for (std::size_t i = 0; i < m.proteins.size(); ++i) {
        const scene::MembraneProtein& p = m.proteins[i];
        if (!(p.abundance.value > 0.0) || (p.per_compartment && *p.per_compartment == 0) || placed(p.molecule.name)) continue;
        refuse(scene::amount_key(m, i), number(p.abundance.value), c, p.molecule.name,
               membrane_reason(baked, mi, c, p.molecule.name));
      }
      if (m.lipids && !placed(m.lipids->molecule.name))
        refuse(key + ".lipids.area_per_lipid", "one lipid per " + number(m.lipids->area_per_lipid) + " Å²", c,
               m.lipids->molecule.name, membrane_reason(baked, mi, c, m.lipids->molecule.name));
      if (m.lipid_patch) {
        double outer = 0.0, inner = 0.0;  // the mix's shares: the base species keeps the rest
        for (const scene::LipidPatchDescription& species : m.lipid_mix) {
          outer += species.outer;
          inner += species.inner;
        }
        if (m.lipid_patch->kinds.empty() && (outer < 1.0 || inner < 1.0) && !placed(m.lipid_patch->name))
          refuse(key + ".lipid_patch", "the patch", c, m.lipid_patch->name, membrane_reason(baked, mi, c, m.lipid_patch->name));
        for (const scene::LipidKind& kind : m.lipid_patch->kinds)
          if (!placed(kind.name))
            refuse(key + ".lipid_patch.kinds." + kind.residue, "the patch's kind", c, kind.name,
                   membrane_reason(baked, mi, c, kind.name));
        if (c.membrane) scene::check_leaflet_shares(scene, mi, c.membrane->outer_kinds, c.membrane->inner_kinds, "the bake keeps");
      }
      for (std::size_t j = 0; j < m.lipid_mix.size(); ++j) {
        const scene::LipidPatchDescription& species = m.lipid_mix[j];
        if (!(species.outer > 0.0 || species.inner > 0.0) || placed(species.name)) continue;
        const bool outer = species.outer > 0.0;
        refuse(key + ".lipid_mix[" + std::to_string(j) + "]." + (outer ? "outer" : "inner"),
               number(outer ? species.outer : species.inner), c, species.name,
               membrane_reason(baked, mi, c, species.name) +
                   " (a species' conformers take only places where they fit among the lipids standing)");
      }
    }
    if (description.soluble) {
      const std::size_t si = description.soluble->index;
      const scene::SolubleDescription& s = scene.solubles.at(si);
      for (std::size_t i = 0; i < s.molecules.size(); ++i) {
        const scene::SolubleMolecule& molecule = s.molecules[i];
        if (!(molecule.abundance.value > 0.0) || placed(molecule.molecule.name)) continue;
        refuse(scene::amount_key(s, i), number(molecule.abundance.value), c, molecule.molecule.name,
               soluble_reason(baked, scene.membranes.size() + si, c, s, molecule.molecule.name));
      }
    }
  }
}

std::vector<std::string> per_compartment_shortfalls(const scene::SceneDescription& scene, const BakedScene& baked) {
  std::vector<std::string> shortfalls;
  for (std::size_t ci = 0; ci < scene.compartments.size() && ci < baked.compartments.size(); ++ci) {
    const auto& membrane = scene.compartments[ci].membrane;
    if (!membrane) continue;
    const scene::MembraneDescription& m = scene.membranes.at(membrane->index);
    for (std::size_t i = 0; i < m.proteins.size(); ++i) {
      const scene::MembraneProtein& p = m.proteins[i];
      if (!p.per_compartment || !(p.abundance.value > 0.0)) continue;
      const std::uint64_t kept = count_of(baked.compartments[ci].copies, p.molecule.name);
      if (kept >= *p.per_compartment) continue;
      shortfalls.push_back(scene::protein_key(m, i, "per_compartment") + ": compartment '" + baked.compartments[ci].name +
                           "' keeps " + std::to_string(kept) + " of the " + std::to_string(*p.per_compartment) +
                           " copies of '" + p.molecule.name + "' per_compartment asks: its tiles placed no more (pack them denser)");
    }
  }
  return shortfalls;
}

}  // namespace nano::scene_bake
