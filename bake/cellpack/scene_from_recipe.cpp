#include "bake/cellpack/scene_from_recipe.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "bake/cellpack/sphere_tree.hpp"
#include "bake/cellpack/structure_files.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/structure/structure_reader.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace fs = std::filesystem;

namespace {

constexpr double kAvogadro = 6.02214076e23;
constexpr double kLitresPerA3 = 1e-27;
constexpr double kA2PerUm2 = 1e8;
constexpr double kTileSize = 191.1;    // 3 periods of the bundled POPC patch (docs/scene.md)
constexpr double kSmallestCube = 250;  // Å: the bundled scenes' cube edge
constexpr double kLargestCube = 1000;  // Å: a set of 64 is then 0.064 µm³ (packing time grows with it)
constexpr double kFewCopiesInARegion = 20;  // below, a count off by more than 10 % is the tiling's lumps
constexpr double kFewCopies = 3;       // in a region: below, the report warns that the bake may place none
constexpr double kCopiesPerSet = 5;    // of the rarest ingredient, where the cubes can grow to hold them
constexpr double kClearance = 5;       // Å, as the bundled solubles
constexpr double kSmallestCompartment = 100;  // Å across: below, no protein fits (a mesh in other units)
// How far a bundled bilayer and its proteins reach into the volume beside it (Å): the bake measures
// 41-58 Å for the POPC patch; a soluble's centre stays this, the clearance and its radius away.
constexpr double kMembraneReach = 50;
constexpr double kTypicalRadius = 30;  // Å, a soluble whose recipe gives no radius (a haemoglobin)
constexpr std::size_t kStandInSpheres = 4096;         // a stand-in is coarse: its sphere tree's finest level up to this
constexpr double kMostCountedSurfaceCopies = 20000;  // per compartment: kept exactly (per_compartment) up to this
constexpr double kSurfaceOverpacking = 1.3;          // tiles packed this much denser than the count they keep

std::string shown(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

std::string percent(double fraction) {
  char b[32];
  std::snprintf(b, sizeof b, "%+.1f %%", 100.0 * fraction);
  return b;
}

// A scene name (letters, digits, '_' and '-', at most 100 characters) for a recipe id.
std::string scene_name(const std::string& id) {
  std::string s;
  for (const char c : id) s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  if (s.empty()) s = "ingredient";
  return s.substr(0, 100);
}

std::string relative_to(const fs::path& file, const fs::path& folder) {
  std::error_code ec;
  const fs::path rel = fs::relative(fs::absolute(file, ec), fs::absolute(folder.empty() ? fs::path(".") : folder, ec), ec);
  return ec || rel.empty() ? fs::absolute(file).string() : rel.generic_string();
}

// What bounds a region (Å²): membranes, which reach into it, and bare meshes, which do not; and,
// for the inside of one sphere or box, its shape, whose free part is known exactly.
struct Walls {
  double membrane_area = 0;
  double bare_area = 0;
  std::optional<double> sphere_radius;  // the region is this sphere's inside
  std::optional<glm::dvec3> box_size;   // the region is this box's inside
};

// A compartment's size as the amounts need it: volume (Å³) and area (Å²).

struct Measure {
  double volume = 0;
  double area = 0;
  glm::dvec3 box_min{0.0}, box_max{0.0};  // where it stands (Å)
};

// v1 recipes nest by geometry alone (HIV-1's capsid inside its envelope): a compartment whose box
// lies inside another's, or two that overlap, would be instanced through each other.
std::string placement_conflict(const Measure& a, const Measure& b) {
  const bool inside = glm::all(glm::greaterThanEqual(b.box_min, a.box_min)) && glm::all(glm::lessThanEqual(b.box_max, a.box_max));
  if (inside) return "inside";
  const bool overlap = glm::all(glm::lessThan(a.box_min, b.box_max)) && glm::all(glm::lessThan(b.box_min, a.box_max));
  return overlap ? "overlapping" : "";
}

class Importer {
public:
  Importer(const Recipe& recipe, const ImportOptions& options)
      : recipe_(recipe), options_(options), structures_(options.structures) {}

  ImportResult run() {
    result_.scene = Json::object();
    Json& s = result_.scene;
    s["format"] = "nanouniverse-scene";
    s["version"] = 1;
    s["description"] = "Imported from the cellPACK recipe " + recipe_.name + " (" + fs::path(recipe_.file).filename().string() + ")";
    s["molecules"] = Json::object();
    double outside_volume = box_volume();
    for (const Compartment& c : recipe_.compartments) add_compartment(c, outside_volume);
    if (recipe_.compartments.empty()) add_box_of_cytoplasm();
    else if (!recipe_.outside.empty()) add_medium(outside_volume);
    if (!missing_.empty()) throw InputError(recipe_.file, "", missing_text());
    if (s["instances"].empty()) throw InputError(recipe_.file, "compartments", "the recipe has no compartment to place; a scene needs one");
    return std::move(result_);
  }

private:
  double box_volume() const {
    if (!recipe_.box_min || !recipe_.box_max) return 0;
    const glm::dvec3 e = *recipe_.box_max - *recipe_.box_min;
    return e.x > 0 && e.y > 0 && e.z > 0 ? e.x * e.y * e.z : 0;
  }

  Measure measure(const Compartment& c, Json& mesh) {
    Measure m;
    if (c.geometry == Compartment::Geometry::sphere) {
      m.volume = 4.0 / 3.0 * std::numbers::pi * c.radius * c.radius * c.radius;
      m.area = 4.0 * std::numbers::pi * c.radius * c.radius;
      // About one triangle per (tile edge)² of surface, at least a few hundred for a round proxy.
      const double triangles = std::clamp(m.area / (kTileSize * kTileSize), 320.0, 200000.0);
      mesh = {{"generate", "sphere"}, {"radius", c.radius}, {"triangles", int(triangles)}};
      m.box_min = c.centre - c.radius;
      m.box_max = c.centre + c.radius;
      return m;
    }
    const fs::path file = mesh_file(c);
    const mesh::ProxyMesh proxy = mesh::read_proxy_mesh(file);
    for (const mesh::Triangle& t : proxy.triangles) {
      const glm::dvec3 a = proxy.positions[t[0]], b = proxy.positions[t[1]], d = proxy.positions[t[2]];
      m.area += 0.5 * glm::length(glm::cross(b - a, d - a));
      m.volume += glm::dot(a, glm::cross(b, d)) / 6.0;
    }
    m.volume = std::abs(m.volume);
    m.box_min = m.box_max = proxy.positions.front();
    for (const glm::dvec3& p : proxy.positions) {
      m.box_min = glm::min(m.box_min, p);
      m.box_max = glm::max(m.box_max, p);
    }
    mesh = {{"file", relative_to(file, options_.scene_folder)}};
    return m;
  }

  fs::path mesh_file(const Compartment& c) const {
    const std::vector<fs::path> candidates =
        recipe_file_candidates(c.mesh_file, fs::path(recipe_.file).parent_path(), options_.read);
    for (const fs::path& p : candidates)
      if (std::error_code ec; fs::is_regular_file(p, ec)) return p;
    std::string tried;
    for (const fs::path& p : candidates) tried += (tried.empty() ? "" : ", ") + p.string();
    throw InputError(c.where, "geom", "mesh '" + c.mesh_file + "' not found (tried " + tried + ")");
  }

  // The scene molecule for ingredient `in` (one per recipe id), its file found among the structures.
  std::string molecule(const Ingredient& in, bool on_surface) {
    const std::string name = scene_name(in.id);
    Json& molecules = result_.scene["molecules"];
    if (molecules.contains(name)) return name;
    Json m = Json::object();
    const StructureFolder::Lookup found = structures_.find(in.structure.empty() ? in.id : in.structure);
    if (found.found) {
      m["file"] = relative_to(*found.found, options_.scene_folder);
      radii_[name] = bounding_radius(structure::read_molecule(*found.found, {}).atoms);
    } else if (std::optional<Json> stand_in = options_.stand_ins ? stand_in_for(in) : std::nullopt) {
      std::vector<structure::Atom> sphere_atoms;
      for (const Json& v : (*stand_in)["spheres"]) sphere_atoms.push_back({.position = {v[0], v[1], v[2]}, .radius = v[3]});
      radii_[name] = bounding_radius(sphere_atoms);
      m["stand_in"] = std::move(*stand_in);
      const std::size_t spheres = m["stand_in"]["spheres"].size();
      stand_ins_[name] = m["stand_in"]["from"].get<std::string>() + ", " + std::to_string(spheres) + (spheres == 1 ? " sphere" : " spheres");
    } else {
      std::string tried;
      for (std::size_t k = 0; k < found.tried.size() && k < 4; ++k) tried += (k ? ", " : "") + found.tried[k];
      if (found.tried.size() > 4) tried += ", … (" + std::to_string(found.tried.size()) + " names)";
      missing_.push_back(in.id + " (" + (in.structure.empty() ? "no structure named; by its id" : in.structure) + "; tried " + tried +
                         (options_.stand_ins ? "; no packing spheres or encapsulating radius to stand in either" + sphere_files_tried(in) : "") +
                         ")");
    }
    if (in.colour) m["colour"] = {in.colour->x, in.colour->y, in.colour->z};
    if (on_surface && in.principal_vector && glm::length(*in.principal_vector) > 0) {
      const glm::dvec3 up = glm::normalize(*in.principal_vector);
      m["up"] = {up.x, up.y, up.z};
    }
    molecules[name] = m;
    return name;
  }

  // A stand-in for `in`'s missing structure, from its packing representation: the finest level of
  // its .sph sphere tree, else its inline spheres, else one sphere of its encapsulating radius.
  std::optional<Json> stand_in_for(const Ingredient& in) const {
    std::vector<glm::dvec4> spheres;
    std::string from;
    if (!in.sphere_file.empty()) {
      const fs::path folder = fs::path(in.file.empty() ? recipe_.file : in.file).parent_path();
      for (const fs::path& p : recipe_file_candidates(in.sphere_file, folder, options_.read)) {
        if (std::error_code ec; !fs::is_regular_file(p, ec)) continue;
        const SphereTree tree = read_sphere_tree(p);
        // The finest level a coarse stand-in needs: at most kStandInSpheres spheres.
        for (const std::vector<glm::dvec4>& level : tree.levels)
          if (level.size() <= kStandInSpheres) spheres = level;
        from = p.filename().string();
        break;
      }
    }
    if (spheres.empty() && !in.spheres.empty()) {
      spheres = in.spheres;
      from = "the recipe's packing spheres";
    }
    if (spheres.empty() && in.encapsulating_radius > 0) {
      spheres = {glm::dvec4(0.0, 0.0, 0.0, in.encapsulating_radius)};
      from = "its encapsulating radius";
    }
    if (spheres.empty()) return std::nullopt;
    Json list = Json::array();
    for (const glm::dvec4& v : spheres) list.push_back({v.x, v.y, v.z, v.w});
    return Json{{"spheres", list}, {"from", from}};
  }

  // Where a stand-in's sphere tree was looked for, for the message that none was found.
  std::string sphere_files_tried(const Ingredient& in) const {
    if (in.sphere_file.empty()) return "";
    const fs::path folder = fs::path(in.file.empty() ? recipe_.file : in.file).parent_path();
    std::string tried;
    for (const fs::path& p : recipe_file_candidates(in.sphere_file, folder, options_.read)) tried += (tried.empty() ? "" : ", ") + p.string();
    return " (its " + in.sphere_file + " is not at " + tried + (options_.read.server_folder.empty() && in.sphere_file.find(':') != std::string::npos
                                                                 ? "; --server FOLDER names a local copy of cellPACK's database)" : ")");
  }

  // The soluble for `ingredients` filling `volume` Å³ within `walls`, the scene's `scene_region`;
  // its report lines. The recipe's copies are those of the whole volume (cellPACK's count), but the
  // bake keeps solubles clear of every wall: they are packed denser in what is left (free_volume),
  // so that the region holds the copies the recipe asked for.
  Json soluble(const std::vector<Ingredient>& ingredients, double volume, const Walls& walls, const std::string& region,
               const std::string& scene_region, int cubes) {
    Json list = Json::array();
    std::vector<std::pair<double, double>> packed;  // per ingredient: radius (Å), copies per Å³
    for (const Ingredient& in : ingredients) {
      if (asks_for_none(in, region)) continue;
      const double copies = in.molarity * kAvogadro * volume * kLitresPerA3 + static_cast<double>(in.count);
      if (volume > 0 && copies < options_.fewest_copies) {
        result_.report.push_back({in.id, region, asked(in), "nothing: left out, " + shown(copies) + " copies in " +
                                  shown(volume * 1e-12) + " µm³ (--fewest-copies " + shown(options_.fewest_copies) + ")", "",
                                  in.not_carried});
        continue;
      }
      const std::string name = molecule(in, false);
      const double radius = radius_of(in, name);
      const double free = free_volume(volume, walls, radius);
      const double mM = volume > 0 ? copies / (kAvogadro * free * kLitresPerA3) * 1000.0 : in.molarity * 1000.0;
      list.push_back({{"molecule", name}, {"concentration_mM", mM}});
      packed.emplace_back(radius, mM * 1e-3 * kAvogadro * kLitresPerA3);
      ImportLine line{in.id, region, asked(in), shown(mM) + " mM", stand_in_of(name), in.not_carried, scene_region, name, copies,
                      volume * 1e-12, false};
      if (volume > 0)
        line.held += " in the " + shown(free * 1e-12) + " µm³ clear of its walls (" + shown(copies) + " copies in " +
                     shown(volume * 1e-12) + " µm³: " + shown(copies / (volume * 1e-12)) + " /µm³)";
      if (in.count > 0 && volume <= 0) line.not_carried.push_back("nbMol " + std::to_string(in.count) + ": the region's volume is unknown");
      // A tiled soluble holds whole copies per cube set; a region that asks for a handful may get
      // none where its boxes sample the set, and the bake then refuses the molecule by name.
      if (volume > 0 && copies < kFewCopies)
        line.note = "only " + shown(copies) + " copies in the region: the bake may place none of it and then refuses it by name "
                    "(--fewest-copies " + shown(kFewCopies) + " leaves such ingredients out, listed)";
      result_.report.push_back(std::move(line));
    }
    const auto [edge, set] = cube_set(packed, cubes);
    return {{"cube_size", edge}, {"cubes", set}, {"molecules", list}, {"clearance", kClearance}};
  }

  // The cube edge and count for ingredients of these radii and densities: 2.2 × the largest radius,
  // at least 250 Å; large enough that one set holds kCopiesPerSet of the rarest (a set holds whole
  // copies: ± ½ copy is ± 10 % at 5), the complete 2-colour set of 64 cubes first, then larger cubes
  // up to kLargestCube (beyond, the bake refuses the ingredient by name: it would place no copy); and
  // 4 × the radius of one that comes less than once a cube, which only a cube's interior can hold
  // then (a 108 Å sphere at 0.08 a cube of 251 Å placed none).
  static std::pair<double, int> cube_set(const std::vector<std::pair<double, double>>& packed, int cubes) {
    double edge = kSmallestCube, rarest = std::numeric_limits<double>::infinity();
    for (const auto& [radius, per_a3] : packed) {
      edge = std::max(edge, std::ceil(2.2 * radius));
      if (per_a3 > 0) rarest = std::min(rarest, per_a3);
    }
    if (std::isfinite(rarest) && cubes * edge * edge * edge < kCopiesPerSet / rarest) {
      cubes = 64;
      edge = std::clamp(std::ceil(std::cbrt(kCopiesPerSet / rarest / cubes)), edge, std::max(edge, kLargestCube));
    }
    for (const auto& [radius, per_a3] : packed)
      if (per_a3 * edge * edge * edge < 1.0) edge = std::max(edge, std::ceil(4.0 * radius));
    return {edge, cubes};
  }

  // The medium fills whole cubes, its region rounded up to them: at an edge of 361 Å the recipe's
  // 8000 Å box became 8303 Å, 12 % more plasma than the recipe holds. The edge from `least` up to
  // 1.5 × it that a whole number of cubes fills the box with best (exactly, along one side or all).
  static double cube_edge_fitting(const glm::dvec3& box, double least) {
    double best = least, best_excess = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis)
      for (double cubes = std::floor(box[axis] / least); cubes >= 1; --cubes) {
        const double edge = box[axis] / cubes;
        if (edge > 1.5 * least) break;
        const glm::dvec3 filled = glm::ceil(box / edge - 1e-9) * edge;
        const double excess = filled.x * filled.y * filled.z / (box.x * box.y * box.z);
        if (excess < best_excess - 1e-12) best = edge, best_excess = excess;
      }
    return best;
  }

  // The part of `volume` a soluble of this radius reaches: each wall keeps it its reach (a
  // membrane's kMembraneReach, a bare mesh's none) plus the clearance and its radius from its
  // triangles: the inside of a sphere or a box shrunk by that depth, else a first-order shell
  // (area × depth), which overstates the loss in a thin box (IgG in BloodPlasma's 300 Å slab: +27 %).
  static double free_volume(double volume, const Walls& walls, double radius) {
    const double molecule = kClearance + (radius > 0 ? radius : kTypicalRadius);
    const double depth = (walls.membrane_area > 0 ? kMembraneReach : 0.0) + molecule;
    double free = volume - walls.membrane_area * (kMembraneReach + molecule) - walls.bare_area * molecule;
    if (walls.sphere_radius) free = 4.0 / 3.0 * std::numbers::pi * std::pow(std::max(*walls.sphere_radius - depth, 0.0), 3);
    if (walls.box_size) {
      const glm::dvec3 inner = glm::max(*walls.box_size - 2.0 * depth, glm::dvec3(0.0));
      free = inner.x * inner.y * inner.z;
    }
    return std::max(free, 0.25 * volume);
  }

  // Left out, and the report says so (its structure is not looked for): an ingredient at molarity
  // 0 and nbMol 0 (recipes keep switched-off ingredients so), and a fibre, which is grown along a
  // path rather than placed as copies (its not-carried note says so).
  bool asks_for_none(const Ingredient& in, const std::string& region) {
    std::string type = in.type;
    std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool fibre = type == "grow" || type == "actine" || type == "fiber" || type == "fibre";
    if (!fibre && (in.molarity > 0 || in.count > 0)) return false;
    result_.report.push_back({in.id, region, asked(in), fibre ? "nothing: a fibre is not placed" : "nothing: left out", "", in.not_carried});
    return true;
  }

  // How far a molecule reaches from its centroid: its structure's or its stand-in's atoms as read
  // here, else the recipe's encapsulating radius (0: unknown).
  double radius_of(const Ingredient& in, const std::string& molecule) const {
    const auto it = radii_.find(molecule);
    return it != radii_.end() ? it->second : in.encapsulating_radius;
  }

  static double bounding_radius(const std::vector<structure::Atom>& atoms) {
    glm::dvec3 centroid(0.0);
    for (const structure::Atom& a : atoms) centroid += a.position;
    centroid /= std::max<double>(1.0, static_cast<double>(atoms.size()));
    double reach = 0;
    for (const structure::Atom& a : atoms) reach = std::max(reach, glm::length(a.position - centroid) + a.radius);
    return reach;
  }

  std::string stand_in_of(const std::string& molecule) const {
    const auto it = stand_ins_.find(molecule);
    return it == stand_ins_.end() ? "" : it->second;
  }

  // Both amounts given: cellPACK places their sum, which some recipes (BloodPlasma 1.0) did not mean —
  // their nbMol is the molarity's count written out — so the report says so and shows both.
  static std::string asked(const Ingredient& in) {
    std::string s;
    if (in.molarity > 0) s += "molarity " + shown(in.molarity) + " M";
    if (in.count > 0) s += (s.empty() ? "" : " + ") + std::string("nbMol ") + std::to_string(in.count);
    if (in.molarity > 0 && in.count > 0) s += " (both given: their sum, as cellPACK places it)";
    return s.empty() ? "nothing (molarity 0, nbMol 0)" : s;
  }

  Json membrane(const Compartment& c, double area) {
    Json proteins = Json::array();
    for (const Ingredient& in : c.surface) {
      if (asks_for_none(in, c.id + " surface")) continue;
      // cellPACK reads a surface molarity per Å² as it reads one per Å³: M · N_A · 10⁻²⁷ copies.
      const double per_um2 = in.molarity * kAvogadro * kLitresPerA3 * kA2PerUm2 +
                             (in.count > 0 && area > 0 ? double(in.count) / (area / kA2PerUm2) : 0.0);
      double depth = 0;
      if (in.offset && in.principal_vector && glm::length(*in.principal_vector) > 0)
        depth = glm::dot(*in.offset, glm::normalize(*in.principal_vector));
      const std::string name = molecule(in, true);
      const double copies = per_um2 * area / kA2PerUm2;
      Json protein = {{"molecule", name}, {"density_per_um2", per_um2}, {"depth", depth}};
      ImportLine line{in.id, c.id + " surface", asked(in), shown(per_um2) + " /µm²", stand_in_of(name), in.not_carried,
                      scene_name(c.id), name, copies, area / kA2PerUm2, true};
      // A chart's compression puts more tiles, so more copies, on some of the surface than its area
      // holds (+15-20 % on a small sphere): a count the farthest-point sampling can keep is kept
      // exactly, from tiles packed a little denser than it.
      if (copies >= 0.5 && copies <= kMostCountedSurfaceCopies) {
        protein["per_compartment"] = std::llround(copies);
        protein["density_per_um2"] = per_um2 * kSurfaceOverpacking;
        line.held = shown(per_um2) + " /µm²: " + std::to_string(std::llround(copies)) + " copies kept on " + shown(area / kA2PerUm2) +
                    " µm² (per_compartment), from tiles packed at " + shown(per_um2 * kSurfaceOverpacking) + " /µm²";
      } else {
        line.held += " (" + shown(copies) + " copies on " + shown(area / kA2PerUm2) + " µm²)";
      }
      line.held += "; depth " + shown(depth) + " Å";
      proteins.push_back(std::move(protein));
      result_.report.push_back(std::move(line));
    }
    Json m = {{"tile_size", kTileSize}, {"proteins", proteins}};
    // Lipids in a neutral grey, so that the recipe's colours stand out against the bilayer.
    m["lipid_patch"] = {{"file", relative_to(options_.lipid_patch, options_.scene_folder)}, {"name", "lipid"}, {"colour", "#c4c4bc"}};
    return m;
  }

  void add_compartment(const Compartment& c, double& outside_volume) {
    if (!c.parent.empty())
      throw InputError(c.where, "", "compartment '" + c.id + "' lies inside '" + c.parent +
                                        "': Nanouniverse's compartment instances do not nest yet");
    if (c.geometry == Compartment::Geometry::none) throw InputError(c.where, "geom", "compartment '" + c.id + "' has no geometry");
    Json mesh;
    const Measure m = measure(c, mesh);
    // cellPACK meshes are in Å; a mesh written in other units (nm, µm, a modeller's 1) arrives far
    // too small to hold a protein, and the bake would only say that nothing fits inside.
    if (const glm::dvec3 extent = m.box_max - m.box_min; std::max({extent.x, extent.y, extent.z}) < kSmallestCompartment)
      throw InputError(c.where, "geom", "compartment '" + c.id + "' is " + shown(std::max({extent.x, extent.y, extent.z})) +
                                            " Å across, too small to hold a protein: cellPACK's meshes are in Å; is this one in nm or "
                                            "µm? (import-cellpack writes a scene whose mesh \"units\" can be set)");
    for (const auto& [other, placed] : placed_) {
      std::string conflict = placement_conflict(placed, m);
      if (conflict.empty()) conflict = placement_conflict(m, placed);
      if (!conflict.empty())
        throw InputError(c.where, "", "compartment '" + c.id + "' and '" + other + "' are " +
                                          (conflict == "inside" ? "nested (one's bounds lie inside the other's)" : "overlapping") +
                                          ": Nanouniverse's compartment instances do not nest or overlap yet");
    }
    placed_.emplace_back(c.id, m);
    outside_volume -= m.volume;
    (options_.lipid_patch.empty() ? walls_.bare_area : walls_.membrane_area) += m.area;
    const std::string name = scene_name(c.id);
    Json comp = {{"mesh", mesh}};
    if (!c.surface.empty() && options_.lipid_patch.empty())
      throw InputError(c.where, "surface", "surface ingredients need a bilayer to stand in: --lipid-patch FILE (e.g. the "
                                           "bundled data/structures/popc_bilayer.pdb.gz)");
    if (!options_.lipid_patch.empty()) {
      result_.scene["membranes"][name] = membrane(c, m.area);
      comp["membrane"] = name;
    }
    Walls walls = options_.lipid_patch.empty() ? Walls{0.0, m.area} : Walls{m.area, 0.0};
    if (c.geometry == Compartment::Geometry::sphere) walls.sphere_radius = c.radius;
    if (Json interior = soluble(c.interior, m.volume, walls, c.id + " interior", name, 16);
        !interior["molecules"].empty()) {
      result_.scene["solubles"][name] = std::move(interior);
      comp["soluble"] = name;
    }
    if (!comp.contains("membrane") && !comp.contains("soluble"))
      throw InputError(c.where, "", "compartment '" + c.id + "' holds nothing: give it a bilayer (--lipid-patch) or interior ingredients");
    result_.scene["compartments"][name] = comp;
    Json instance = {{"compartment", name}};
    if (c.geometry == Compartment::Geometry::sphere && glm::length(c.centre) > 0)
      instance["transform"] = {{"translate", {c.centre.x, c.centre.y, c.centre.z}}};
    result_.scene["instances"].push_back(instance);
  }

  // A recipe of its cytoplasm alone (BloodPlasma) fills its bounding box: a box compartment whose
  // interior is the cytoplasm, kept clear of the box's faces like any bare wall.
  void add_box_of_cytoplasm() {
    if (!recipe_.box_min || !recipe_.box_max || !(box_volume() > 0))
      throw InputError(recipe_.file, "", "the recipe has no compartment and no bounding box: nothing gives its cytoplasm a size");
    const glm::dvec3 size = *recipe_.box_max - *recipe_.box_min, centre = 0.5 * (*recipe_.box_max + *recipe_.box_min);
    const Walls walls{0.0, 2.0 * (size.x * size.y + size.y * size.z + size.z * size.x), std::nullopt, size};
    Json cytoplasm = soluble(recipe_.outside, box_volume(), walls, "cytoplasm (the recipe's box)", "cytoplasm", 16);
    if (cytoplasm["molecules"].empty()) throw InputError(recipe_.file, "", "the recipe asks for no molecule anywhere");
    result_.scene["solubles"]["cytoplasm"] = std::move(cytoplasm);
    result_.scene["compartments"]["cytoplasm"] = {{"mesh", {{"generate", "box"}, {"size", {size.x, size.y, size.z}}}},
                                                  {"soluble", "cytoplasm"}};
    Json instance = {{"compartment", "cytoplasm"}};
    if (glm::length(centre) > 0) instance["transform"] = {{"translate", {centre.x, centre.y, centre.z}}};
    result_.scene["instances"].push_back(instance);
  }

  void add_medium(double volume) {
    // The medium's cube set must be complete: 2 face colours, 2⁶ cubes.
    Json outside = soluble(recipe_.outside, volume, walls_, "outside", "medium", 64);
    if (outside["molecules"].empty()) return;
    if (recipe_.box_min && recipe_.box_max)
      outside["cube_size"] = cube_edge_fitting(*recipe_.box_max - *recipe_.box_min, outside["cube_size"].get<double>());
    result_.scene["solubles"]["outside"] = std::move(outside);
    Json medium = {{"soluble", "outside"}};
    if (recipe_.box_min && recipe_.box_max)
      medium["region"] = {{recipe_.box_min->x, recipe_.box_min->y, recipe_.box_min->z},
                          {recipe_.box_max->x, recipe_.box_max->y, recipe_.box_max->z}};
    result_.scene["medium"] = medium;
  }

  std::string missing_text() const {
    std::string s = std::to_string(missing_.size()) + " ingredient structure(s) not found in " + options_.structures.string() + ":";
    for (const std::string& m : missing_) s += "\n  " + m;
    if (!options_.stand_ins) s += "\n(--stand-ins draws each from its packing spheres until its structure is at hand)";
    return s;
  }

  const Recipe& recipe_;
  const ImportOptions& options_;
  StructureFolder structures_;
  ImportResult result_;
  std::vector<std::string> missing_;
  std::vector<std::pair<std::string, Measure>> placed_;  // compartments placed so far
  Walls walls_;  // every compartment's surface (the medium keeps clear of them)
  std::map<std::string, std::string> stand_ins_;
  std::map<std::string, double> radii_;  // scene molecule → its bounding radius (Å), as read  // scene molecule → what it stands in with
};

}  // namespace

ImportResult scene_from_recipe(const Recipe& recipe, const ImportOptions& options) { return Importer(recipe, options).run(); }

std::string report_text(const Recipe& recipe, const ImportResult& result) {
  std::string s = "cellPACK recipe " + recipe.name + " (" + (recipe.format == RecipeFormat::v1 ? "v1" : "v2") + " " + recipe.version + ")\n";
  for (const std::string& n : recipe.not_carried) s += "not carried over: " + n + "\n";
  const auto both = [](const std::vector<Ingredient>& list) {
    return std::any_of(list.begin(), list.end(), [](const Ingredient& in) { return in.molarity > 0 && in.count > 0; });
  };
  bool any_both = both(recipe.outside);
  for (const Compartment& c : recipe.compartments) any_both = any_both || both(c.surface) || both(c.interior);
  if (any_both)
    s += "note: ingredients below give both a molarity and an nbMol; cellPACK places their sum, and so does this scene. Where a "
         "recipe's nbMol is its molarity's count written out (BloodPlasma 1.0 does so), that is twice what it means: set one to 0\n";
  for (const ImportLine& l : result.report) {
    s += l.ingredient + " [" + l.region + "]: asked " + l.asked + "; holds " + l.held + "\n";
    if (!l.stand_in.empty()) s += "  STAND-IN (structure missing): drawn as " + l.stand_in + "\n";
    if (!l.note.empty()) s += "  note: " + l.note + "\n";
    for (const std::string& n : l.not_carried) s += "  not carried over: " + n + "\n";
  }
  return s;
}

Json report_json(const ImportResult& result, const HeldCopies* held) {
  Json list = Json::array();
  for (const ImportLine& l : result.report) {
    Json j = {{"ingredient", l.ingredient}, {"region", l.region}, {"asked", l.asked}, {"holds", l.held},
              {"not_carried", l.not_carried}};
    if (!l.stand_in.empty()) j["stand_in"] = l.stand_in;
    if (!l.note.empty()) j["note"] = l.note;
    if (l.expected_copies > 0) {
      j["scene"] = {{"region", l.scene_region}, {"molecule", l.molecule}};
      j["copies_asked"] = l.expected_copies;
      j[l.surface ? "area_um2" : "volume_um3"] = l.measure;
      if (held) {
        const auto it = held->find({l.scene_region, l.molecule});
        j["copies_placed"] = it == held->end() ? 0.0 : it->second;
      }
    }
    list.push_back(std::move(j));
  }
  return list;
}

std::string copy_number_check(const ImportResult& result, const HeldCopies& held, int& off) {
  off = 0;
  std::string s = "copy numbers against the recipe (within 10 %):\n";
  for (const ImportLine& l : result.report) {
    if (!(l.expected_copies > 0) || !(l.measure > 0)) continue;
    const auto it = held.find({l.scene_region, l.molecule});
    const double copies = it == held.end() ? 0.0 : it->second;
    const double ratio = copies / l.expected_copies;
    const bool within = std::abs(ratio - 1.0) <= 0.1;
    // A whole set of tiles holds whole copies: a handful asked cannot come closer than one copy.
    const bool one_copy = std::abs(copies - l.expected_copies) <= 1.0;
    s += "  " + l.ingredient + " [" + l.region + "]: " + shown(copies) + " of " + shown(l.expected_copies) + " copies, " +
         shown(copies / l.measure) + " of " + shown(l.expected_copies / l.measure) + (l.surface ? " /µm²" : " /µm³") + " (" +
         percent(ratio - 1.0) + ")";
    if (within || one_copy) {
      s += " ok\n";
      continue;
    }
    ++off;
    if (l.surface)
      s += " OFF: the membrane's tiles could not hold more without clashes (see the densities above)\n";
    else if (l.expected_copies < kFewCopiesInARegion)
      s += " OFF: a handful in this region: a tiled soluble holds whole copies in each cube and the region holds parts of "
           "only some cubes of the set, so a rare ingredient comes in lumps (a larger region averages them out)\n";
    else
      s += " OFF: the cube set packs only so densely without clashes, or the region is too thin for it beside its walls "
           "(see the densities above)\n";
  }
  return s;
}

}  // namespace nano::cellpack
