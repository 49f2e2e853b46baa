#include "bake/cellpack/scene_from_recipe.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include <glm/geometric.hpp>

#include "bake/cellpack/structure_files.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace fs = std::filesystem;

namespace {

constexpr double kAvogadro = 6.02214076e23;
constexpr double kLitresPerA3 = 1e-27;
constexpr double kA2PerUm2 = 1e8;
constexpr double kTileSize = 191.1;    // 3 periods of the bundled POPC patch (docs/scene.md)
constexpr double kSmallestCube = 250;  // Å: the bundled scenes' cube edge
constexpr double kClearance = 5;       // Å, as the bundled solubles

std::string shown(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
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

// A compartment's size as the amounts need it: volume (Å³) and area (Å²).
struct Measure {
  double volume = 0;
  double area = 0;
};

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
    if (!recipe_.outside.empty()) add_medium(outside_volume);
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
    mesh = {{"file", relative_to(file, options_.scene_folder)}};
    return m;
  }

  fs::path mesh_file(const Compartment& c) const {
    const std::string ext = fs::path(c.mesh_file).extension().string();
    if (ext == ".dae" || ext == ".DAE")
      throw InputError(c.where, "geom", "Collada mesh '" + c.mesh_file + "' is not read yet: convert it to .obj, .ply, .off or .stl");
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
    if (!found.found) {
      std::string tried;
      for (std::size_t k = 0; k < found.tried.size() && k < 4; ++k) tried += (k ? ", " : "") + found.tried[k];
      if (found.tried.size() > 4) tried += ", … (" + std::to_string(found.tried.size()) + " names)";
      missing_.push_back(in.id + " (" + (in.structure.empty() ? "no structure named; by its id" : in.structure) + "; tried " + tried + ")");
    } else {
      m["file"] = relative_to(*found.found, options_.scene_folder);
    }
    if (in.colour) m["colour"] = {in.colour->x, in.colour->y, in.colour->z};
    if (on_surface && in.principal_vector && glm::length(*in.principal_vector) > 0) {
      const glm::dvec3 up = glm::normalize(*in.principal_vector);
      m["up"] = {up.x, up.y, up.z};
    }
    molecules[name] = m;
    return name;
  }

  // The soluble for `ingredients` filling `volume` Å³, named `name`; its report lines.
  Json soluble(const std::vector<Ingredient>& ingredients, double volume, const std::string& region, int cubes) {
    Json list = Json::array();
    double largest = 0;
    for (const Ingredient& in : ingredients) {
      const double from_count = in.count > 0 && volume > 0 ? double(in.count) / (kAvogadro * volume * kLitresPerA3) * 1000.0 : 0.0;
      const double mM = in.molarity * 1000.0 + from_count;
      list.push_back({{"molecule", molecule(in, false)}, {"concentration_mM", mM}});
      largest = std::max(largest, in.encapsulating_radius);
      ImportLine line{in.id, region, asked(in), shown(mM) + " mM", in.not_carried};
      if (volume > 0) line.held += " (" + shown(mM * 1e-3 * kAvogadro * volume * kLitresPerA3) + " copies in " + shown(volume * 1e-12) + " µm³)";
      if (in.count > 0 && volume <= 0) line.not_carried.push_back("nbMol " + std::to_string(in.count) + ": the region's volume is unknown");
      result_.report.push_back(std::move(line));
    }
    return {{"cube_size", std::max(kSmallestCube, std::ceil(2.2 * largest))}, {"cubes", cubes}, {"molecules", list}, {"clearance", kClearance}};
  }

  static std::string asked(const Ingredient& in) {
    std::string s;
    if (in.molarity > 0) s += "molarity " + shown(in.molarity) + " M";
    if (in.count > 0) s += (s.empty() ? "" : " + ") + std::string("nbMol ") + std::to_string(in.count);
    return s.empty() ? "nothing (molarity 0, nbMol 0)" : s;
  }

  Json membrane(const Compartment& c, double area) {
    Json proteins = Json::array();
    for (const Ingredient& in : c.surface) {
      // cellPACK reads a surface molarity per Å² as it reads one per Å³: M · N_A · 10⁻²⁷ copies.
      const double per_um2 = in.molarity * kAvogadro * kLitresPerA3 * kA2PerUm2 +
                             (in.count > 0 && area > 0 ? double(in.count) / (area / kA2PerUm2) : 0.0);
      double depth = 0;
      if (in.offset && in.principal_vector && glm::length(*in.principal_vector) > 0)
        depth = glm::dot(*in.offset, glm::normalize(*in.principal_vector));
      proteins.push_back({{"molecule", molecule(in, true)}, {"density_per_um2", per_um2}, {"depth", depth}});
      ImportLine line{in.id, c.id + " surface", asked(in), shown(per_um2) + " /µm²", in.not_carried};
      line.held += " (" + shown(per_um2 * area / kA2PerUm2) + " copies on " + shown(area / kA2PerUm2) + " µm²; depth " + shown(depth) + " Å)";
      result_.report.push_back(std::move(line));
    }
    Json m = {{"tile_size", kTileSize}, {"proteins", proteins}};
    m["lipid_patch"] = {{"file", relative_to(options_.lipid_patch, options_.scene_folder)}, {"name", "lipid"}};
    return m;
  }

  void add_compartment(const Compartment& c, double& outside_volume) {
    if (!c.parent.empty())
      throw InputError(c.where, "", "compartment '" + c.id + "' lies inside '" + c.parent +
                                        "': Nanouniverse's compartment instances do not nest yet");
    if (c.geometry == Compartment::Geometry::none) throw InputError(c.where, "geom", "compartment '" + c.id + "' has no geometry");
    Json mesh;
    const Measure m = measure(c, mesh);
    outside_volume -= m.volume;
    const std::string name = scene_name(c.id);
    Json comp = {{"mesh", mesh}};
    if (!c.surface.empty() && options_.lipid_patch.empty())
      throw InputError(c.where, "surface", "surface ingredients need a bilayer to stand in: --lipid-patch FILE (e.g. the "
                                           "bundled data/structures/popc_bilayer.pdb.gz)");
    if (!options_.lipid_patch.empty()) {
      result_.scene["membranes"][name] = membrane(c, m.area);
      comp["membrane"] = name;
    }
    if (!c.interior.empty()) {
      result_.scene["solubles"][name] = soluble(c.interior, m.volume, c.id + " interior", 16);
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

  void add_medium(double volume) {
    // The medium's cube set must be complete: 2 face colours, 2⁶ cubes.
    result_.scene["solubles"]["outside"] = soluble(recipe_.outside, volume, "outside", 64);
    Json medium = {{"soluble", "outside"}};
    if (recipe_.box_min && recipe_.box_max)
      medium["region"] = {{recipe_.box_min->x, recipe_.box_min->y, recipe_.box_min->z},
                          {recipe_.box_max->x, recipe_.box_max->y, recipe_.box_max->z}};
    result_.scene["medium"] = medium;
  }

  std::string missing_text() const {
    std::string s = std::to_string(missing_.size()) + " ingredient structure(s) not found in " + options_.structures.string() + ":";
    for (const std::string& m : missing_) s += "\n  " + m;
    return s;
  }

  const Recipe& recipe_;
  const ImportOptions& options_;
  StructureFolder structures_;
  ImportResult result_;
  std::vector<std::string> missing_;
};

}  // namespace

ImportResult scene_from_recipe(const Recipe& recipe, const ImportOptions& options) { return Importer(recipe, options).run(); }

std::string report_text(const Recipe& recipe, const ImportResult& result) {
  std::string s = "cellPACK recipe " + recipe.name + " (" + (recipe.format == RecipeFormat::v1 ? "v1" : "v2") + " " + recipe.version + ")\n";
  for (const std::string& n : recipe.not_carried) s += "not carried over: " + n + "\n";
  for (const ImportLine& l : result.report) {
    s += l.ingredient + " [" + l.region + "]: asked " + l.asked + "; holds " + l.held + "\n";
    for (const std::string& n : l.not_carried) s += "  not carried over: " + n + "\n";
  }
  return s;
}

}  // namespace nano::cellpack
