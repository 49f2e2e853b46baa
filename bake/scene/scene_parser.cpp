#include "bake/scene/scene_parser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "bake/scene/effects_parser.hpp"
#include "common/json_cursor.hpp"
#include "bake/scene/random_placement.hpp"
#include "bake/scene/transform_parser.hpp"

namespace nano::scene {
namespace {

constexpr std::int64_t max_tile_colours = 16;
constexpr std::int64_t max_triangles = 100'000'000;
constexpr std::int64_t max_copies_per_placement = 10'000'000;
// Names are part of every key path below them, and each checked value keeps its path.
constexpr std::size_t max_name_length = 100;

// Blames `owner` (the map, so that the message does not repeat a megabyte-long name).
void check_name_length(const JsonCursor& owner, const std::string& name) {
  if (name.size() > max_name_length)
    owner.fail("the name \"" + name.substr(0, 20) + "...\" has " + std::to_string(name.size()) +
               " characters; a name may have at most " + std::to_string(max_name_length));
}

// Names appear in key paths, so they may not contain the path separators "." "[" "]".
void check_name(const JsonCursor& map, const std::string& name) {
  check_name_length(map, name);
  const bool ok = !name.empty() && name.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
                                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") == std::string::npos;
  if (!ok)
    map.fail("name \"" + name + "\" must be non-empty and use only letters, digits, '_' and '-'");
}

std::filesystem::path resolve_path(const JsonCursor& c, const std::filesystem::path& folder) {
  const std::filesystem::path p(c.non_empty_string());
  return p.is_absolute() ? p.lexically_normal() : (folder / p).lexically_normal();
}

// The names of one finished map (molecules, membranes, ...) and where each stands in its vector,
// so that resolving a reference is no search (10^5 instances may name one of 10^5 compartments).
template <class Named>
class Defined {
public:
  explicit Defined(const std::vector<Named>& all) : all_(all) {
    for (std::size_t i = 0; i < all.size(); ++i) index_.emplace(all[i].name, i);  // the first of a name wins
  }
  const std::vector<Named>& all() const { return all_; }
  const std::size_t* find(const std::string& name) const {
    const auto it = index_.find(name);
    return it == index_.end() ? nullptr : &it->second;
  }

private:
  const std::vector<Named>& all_;                             // complete: not changed while this lives
  std::unordered_map<std::string_view, std::size_t> index_;  // views of all_'s names
};

template <class Named>
NameRef resolve(const JsonCursor& c, const Defined<Named>& defined, const std::string& kind) {
  const std::string name = c.string();
  if (const std::size_t* i = defined.find(name)) return {name, *i};
  constexpr std::size_t listed = 10;
  std::string known;
  for (std::size_t i = 0; i < defined.all().size() && i < listed; ++i)
    known += (known.empty() ? "" : ", ") + defined.all()[i].name;
  if (defined.all().size() > listed) known += ", ... (" + std::to_string(defined.all().size()) + " in all)";
  c.fail("unknown " + kind + " \"" + name.substr(0, 100) + "\" (" +
         (known.empty() ? "none are defined" : "defined: " + known) + ")");
}

int hex_digit(char ch) {
  if (ch >= '0' && ch <= '9') return ch - '0';
  if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
  if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
  return -1;
}

glm::dvec3 parse_colour(const JsonCursor& c) {
  if (c.json().is_string()) {
    const std::string s = c.string();
    glm::dvec3 rgb(0.0);
    bool ok = s.size() == 7 && s[0] == '#';
    for (int i = 0; ok && i < 3; ++i) {
      const int hi = hex_digit(s[1 + 2 * i]), lo = hex_digit(s[2 + 2 * i]);
      ok = hi >= 0 && lo >= 0;
      rgb[i] = (hi * 16 + lo) / 255.0;
    }
    if (!ok) c.fail("expected a colour \"#rrggbb\" or [r, g, b] in [0, 1], got " + c.shown());
    return rgb;
  }
  if (!c.json().is_array() || c.json().size() != 3)
    c.fail("expected a colour \"#rrggbb\" or [r, g, b] in [0, 1], got " + c.shown());
  const auto e = c.elements();
  return {e[0].number_between(0.0, 1.0), e[1].number_between(0.0, 1.0), e[2].number_between(0.0, 1.0)};
}

// "stand_in": {"spheres": [[x, y, z, r], ...], "from": "..."}: a molecule drawn as spheres, no structure.
void parse_stand_in(const JsonCursor& c, MoleculeDescription& m) {
  c.only_keys({"spheres", "from"});
  m.stand_in_from = c.required("from").non_empty_string();
  const JsonCursor spheres = c.required("spheres");
  const auto list = spheres.elements(1);
  if (list.size() > kMaxStandInSpheres)
    spheres.fail("a stand-in has at most " + std::to_string(kMaxStandInSpheres) + " spheres, got " + std::to_string(list.size()));
  for (const JsonCursor& sphere : list) {
    const glm::dvec4 v = sphere.vec4();
    if (!(v.w > 0.0) || v.w > 1000.0) sphere.fail("a sphere's radius must be in (0, 1000] Å, got " + sphere.shown());
    if (glm::length(glm::dvec3(v)) > 1e4) sphere.fail("a stand-in's sphere lies more than 10⁴ Å from its molecule's origin: " + sphere.shown());
    m.stand_in_spheres.push_back(v);
  }
}

MoleculeDescription parse_molecule(const std::string& name, const JsonCursor& c, const std::filesystem::path& folder) {
  c.only_keys({"file", "stand_in", "colour", "up", "all_models", "keep_water", "hydrogens"});
  MoleculeDescription m;
  m.name = name;
  if (c.has("file") == c.has("stand_in"))
    c.fail("a molecule has either a structure \"file\" or a \"stand_in\" (spheres standing in for a missing structure), "
           "exactly one of them");
  if (const auto stand_in = c.optional("stand_in")) parse_stand_in(*stand_in, m);
  else m.file = resolve_path(c.required("file"), folder);
  if (const auto colour = c.optional("colour")) m.colour = parse_colour(*colour);
  if (const auto up = c.optional("up")) {
    if (up->json().is_string()) {
      if (up->string() != "principal") up->fail("expected \"principal\" or [x, y, z], got " + up->shown());
    } else {
      m.up_axis = up->unit_vec3();
    }
  }
  if (const auto v = c.optional("all_models")) m.all_models = v->boolean();
  if (const auto v = c.optional("keep_water")) m.keep_water = v->boolean();
  if (const auto v = c.optional("hydrogens")) m.keep_hydrogens = v->boolean();
  return m;
}

// A Wang set with k colours on each of `sides` sides is complete at k^sides tiles; a scanline
// (or voxel-order) fill knows `known_sides` sides of each new tile and needs at least one tile
// for each of their k^known_sides combinations.
int parse_tile_count(const JsonCursor& owner, const char* count_key, const char* colour_key, int colours,
                     int default_count, int known_sides, int sides) {
  std::int64_t min = 1, max = 1;
  for (int i = 0; i < known_sides; ++i) min *= colours;
  for (int i = 0; i < sides; ++i) max *= colours;
  if (const auto count = owner.optional(count_key)) return static_cast<int>(count->integer_between(min, max));
  if (default_count < min || default_count > max)
    owner.required(colour_key).fail("with " + std::to_string(colours) + " colours the default of " +
                                    std::to_string(default_count) + " is not a valid set size; give \"" + count_key +
                                    "\" in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return default_count;
}

// Exactly one of two keys that say the same amount in different units; returns which one and its value.
std::pair<bool, double> parse_one_amount(const JsonCursor& c, const char* first, const char* second) {
  const bool has_first = c.has(first), has_second = c.has(second);
  if (has_first == has_second)
    c.fail(std::string("expected exactly one of \"") + first + "\" and \"" + second + "\", got " +
           (has_first ? "both" : "neither"));
  return {has_first, c.required(has_first ? first : second).number_at_least(0.0)};
}

LipidPatchDescription parse_lipid_patch(const JsonCursor& patch, const std::filesystem::path& folder) {
  LipidPatchDescription p;
  p.file = resolve_path(patch.required("file"), folder);
  if (const auto n = patch.optional("name")) {
    p.name = n->string();
    check_name(*n, p.name);
  }
  if (const auto colour = patch.optional("colour")) p.colour = parse_colour(*colour);
  if (const auto clearance = patch.optional("clearance")) p.clearance = clearance->number_between(0.1, 2.0);
  return p;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& n : names) joined += (joined.empty() ? "'" : ", '") + n + "'";
  return joined;
}

// "kinds": residue name -> {"name", "colour"}; every kind's name its own.
std::vector<LipidKind> parse_lipid_kinds(const JsonCursor& kinds) {
  std::vector<LipidKind> parsed;
  for (const auto& [residue, k] : kinds.members()) {
    k.only_keys({"name", "colour"});
    if (residue.empty() || residue.size() > 4)
      k.fail("a kind is keyed by its residue name in the patch file (1 to 4 characters)");
    LipidKind kind{residue, residue, std::nullopt};
    if (const auto n = k.optional("name")) {
      kind.name = n->string();
      check_name(*n, kind.name);
    }
    if (const auto colour = k.optional("colour")) kind.colour = parse_colour(*colour);
    for (const LipidKind& other : parsed)
      if (other.name == kind.name) k.fail("two kinds report under the name '" + kind.name + "'");
    parsed.push_back(kind);
  }
  if (parsed.empty()) kinds.fail("expected at least one kind");
  return parsed;
}

// One leaflet of "leaflets": {"mol_percent": {kind: %}, "area_per_lipid": Å²}, its shares adding up to 100.
LeafletComposition parse_leaflet(const JsonCursor& leaflet, const std::vector<std::string>& kind_names) {
  leaflet.only_keys({"mol_percent", "area_per_lipid"});
  LeafletComposition composition;
  const JsonCursor shares = leaflet.required("mol_percent");
  double sum = 0.0;
  for (const auto& [kind, share] : shares.members()) {
    if (std::find(kind_names.begin(), kind_names.end(), kind) == kind_names.end())
      share.fail("no kind of this patch is named '" + kind + "' (its kinds: " + join_names(kind_names) + ")");
    composition.mol_percent.emplace_back(kind, share.number_between(0.0, 100.0));
    sum += composition.mol_percent.back().second;
  }
  if (std::abs(sum - 100.0) > 0.5) shares.fail("the kinds' mole percents add up to " + shown_number(sum) + ", not 100");
  composition.area_per_lipid = leaflet.required("area_per_lipid").number_between(15.0, 150.0);
  return composition;
}

// The membrane's "lipid_patch": one kind named by `name`, or several by residue name (`kinds`), and
// optionally the composition asked of each leaflet.
LipidPatchDescription parse_base_patch(const JsonCursor& patch, const std::filesystem::path& folder) {
  patch.only_keys({"file", "name", "colour", "clearance", "kinds", "leaflets"});
  LipidPatchDescription p = parse_lipid_patch(patch, folder);
  std::vector<std::string> kind_names{p.name};
  if (const auto kinds = patch.optional("kinds")) {
    for (const char* own : {"name", "colour"})
      if (const auto key = patch.optional(own)) key->fail("a patch of several kinds names and colours each in \"kinds\"");
    p.kinds = parse_lipid_kinds(*kinds);
    kind_names.clear();
    for (const LipidKind& kind : p.kinds) kind_names.push_back(kind.name);
  }
  if (const auto leaflets = patch.optional("leaflets")) {
    leaflets->only_keys({"outer", "inner"});
    p.outer_leaflet = parse_leaflet(leaflets->required("outer"), kind_names);
    p.inner_leaflet = parse_leaflet(leaflets->required("inner"), kind_names);
  }
  return p;
}

MembraneDescription parse_membrane(const std::string& name, const JsonCursor& c,
                                   const Defined<MoleculeDescription>& molecules, const std::filesystem::path& folder) {
  c.only_keys({"tile_size", "edge_colours", "tiles", "proteins", "lipids", "lipid_patch", "lipid_mix"});
  MembraneDescription m;
  m.name = name;
  m.tile_size = c.required("tile_size").number_greater_than(0.0);
  if (const auto k = c.optional("edge_colours")) m.edge_colours = static_cast<int>(k->integer_between(1, max_tile_colours));
  m.tiles = parse_tile_count(c, "tiles", "edge_colours", m.edge_colours, m.tiles, 2, 4);
  if (const auto proteins = c.optional("proteins")) {
    for (const JsonCursor& p : proteins->elements()) {
      p.only_keys({"molecule", "density_per_um2", "copies_per_tile", "depth", "per_compartment"});
      MembraneProtein protein;
      protein.molecule = resolve(p.required("molecule"), molecules, "molecule");
      const auto [per_area, value] = parse_one_amount(p, "density_per_um2", "copies_per_tile");
      protein.abundance = {per_area ? SurfaceAbundance::Unit::per_um2 : SurfaceAbundance::Unit::per_tile, value};
      if (const auto depth = p.optional("depth")) protein.depth = depth->number();
      if (const auto n = p.optional("per_compartment")) protein.per_compartment = static_cast<std::uint64_t>(n->integer_between(0, 1'000'000'000));
      m.proteins.push_back(protein);
    }
  }
  if (const auto lipids = c.optional("lipids")) {
    lipids->only_keys({"molecule", "area_per_lipid", "leaflet_offset"});
    LipidFill fill;
    fill.molecule = resolve(lipids->required("molecule"), molecules, "molecule");
    fill.area_per_lipid = lipids->required("area_per_lipid").number_greater_than(0.0);
    fill.leaflet_offset = lipids->required("leaflet_offset").number_at_least(0.0);
    m.lipids = fill;
  }
  if (const auto patch = c.optional("lipid_patch")) {
    if (m.lipids) patch->fail("give either \"lipids\" (one pose, a surface density) or \"lipid_patch\", not both");
    m.lipid_patch = parse_base_patch(*patch, folder);
  }
  if (const auto mix = c.optional("lipid_mix")) {
    if (!m.lipid_patch) mix->fail("a \"lipid_mix\" needs the \"lipid_patch\" whose places it takes");
    if (!m.lipid_patch->kinds.empty() || m.lipid_patch->outer_leaflet)
      mix->fail("a \"lipid_mix\" takes places of a patch of one kind; a patch of several kinds gives its "
                "composition in \"lipid_patch.leaflets\"");
    double outer = 0.0, inner = 0.0;
    for (const JsonCursor& e : mix->elements()) {
      e.only_keys({"file", "name", "colour", "clearance", "outer", "inner"});
      LipidPatchDescription species = parse_lipid_patch(e, folder);
      species.outer = e.required("outer").number_between(0.0, 1.0);
      species.inner = e.required("inner").number_between(0.0, 1.0);
      outer += species.outer;
      inner += species.inner;
      if (outer > 1.0 + 1e-9 || inner > 1.0 + 1e-9) e.fail("the mix's fractions add up to more than 1 in a leaflet");
      if (species.name == m.lipid_patch->name) e.required("name").fail("a mixed species needs a name of its own");
      m.lipid_mix.push_back(species);
    }
  }
  if (m.proteins.empty() && !m.lipids && !m.lipid_patch)
    c.fail("a membrane needs \"proteins\", \"lipids\" or \"lipid_patch\"");
  return m;
}

SolubleDescription parse_soluble(const std::string& name, const JsonCursor& c,
                                 const Defined<MoleculeDescription>& molecules) {
  c.only_keys({"cube_size", "face_colours", "cubes", "molecules", "clearance"});
  SolubleDescription s;
  s.name = name;
  s.cube_size = c.required("cube_size").number_greater_than(0.0);
  if (const auto k = c.optional("face_colours")) s.face_colours = static_cast<int>(k->integer_between(1, max_tile_colours));
  s.cubes = parse_tile_count(c, "cubes", "face_colours", s.face_colours, s.cubes, 3, 6);
  for (const JsonCursor& e : c.required("molecules").elements(1)) {
    e.only_keys({"molecule", "concentration_mM", "copies_per_um3"});
    SolubleMolecule molecule;
    molecule.molecule = resolve(e.required("molecule"), molecules, "molecule");
    const auto [molar, value] = parse_one_amount(e, "concentration_mM", "copies_per_um3");
    molecule.abundance = {molar ? VolumeAbundance::Unit::millimolar : VolumeAbundance::Unit::per_um3, value};
    s.molecules.push_back(molecule);
  }
  if (const auto clearance = c.optional("clearance")) s.clearance = clearance->number_at_least(0.0);
  return s;
}

MeshSource::Uv parse_uv_policy(const JsonCursor& c) {
  const std::string text = c.string();
  if (text == "auto") return MeshSource::Uv::automatic;
  if (text == "keep") return MeshSource::Uv::keep;
  if (text == "generate") return MeshSource::Uv::generate;
  c.fail("expected \"auto\", \"keep\" or \"generate\", got " + c.shown());
}

double parse_unit(const JsonCursor& c) {
  const std::string text = c.string();
  if (text == "A" || text == "Å" || text == "angstrom") return 1.0;
  if (text == "nm") return 10.0;
  if (text == "um" || text == "µm") return 1e4;
  c.fail("expected \"A\", \"nm\" or \"um\", got " + c.shown());
}

// "remesh": "auto" | "off" | {"edge": Å}.
void parse_remesh(const JsonCursor& c, MeshSource& mesh) {
  if (c.json().is_object()) {
    c.only_keys({"edge"});
    mesh.remesh = MeshSource::Remesh::edge;
    mesh.remesh_edge = c.required("edge").number_greater_than(0.0);
    return;
  }
  const std::string text = c.json().is_string() ? c.string() : std::string();
  if (text == "auto") mesh.remesh = MeshSource::Remesh::automatic;
  else if (text == "off") mesh.remesh = MeshSource::Remesh::off;
  else c.fail("expected \"auto\", \"off\" or {\"edge\": Å}, got " + c.shown());
}

// Keys every mesh takes: its UV policy, repair, remeshing and a target size.
void parse_mesh_size_and_uvs(const JsonCursor& c, MeshSource& mesh) {
  if (const auto uv = c.optional("uv")) mesh.uv = parse_uv_policy(*uv);
  if (const auto remesh = c.optional("remesh")) {
    parse_remesh(*remesh, mesh);
    if (mesh.remesh == MeshSource::Remesh::edge && mesh.uv == MeshSource::Uv::keep)
      remesh->fail("a remeshed mesh loses its UVs: not with \"uv\": \"keep\"");
  }
  if (const auto repair = c.optional("repair")) {
    mesh.repair = repair->boolean();
    if (mesh.repair && mesh.uv == MeshSource::Uv::keep) repair->fail("a repaired mesh loses its UVs: not with \"uv\": \"keep\"");
  }
  if (c.has("diameter") && c.has("volume")) c.fail("give \"diameter\" or \"volume\", not both");
  if (const auto d = c.optional("diameter")) mesh.diameter = d->number_greater_than(0.0);
  if (const auto v = c.optional("volume")) mesh.volume = v->number_greater_than(0.0);
}

MeshSource parse_mesh(const JsonCursor& c, const std::filesystem::path& folder) {
  const bool from_file = c.has("file"), generated = c.has("generate");
  if (from_file == generated) c.fail("expected exactly one of \"file\" and \"generate\"");
  MeshSource mesh;
  if (from_file) {
    c.only_keys({"file", "units", "diameter", "volume", "uv", "repair", "remesh"});
    mesh.file = resolve_path(c.required("file"), folder);
    if (const auto units = c.optional("units")) mesh.unit = parse_unit(*units);
    parse_mesh_size_and_uvs(c, mesh);
    return mesh;
  }
  const JsonCursor kind = c.required("generate");
  const std::string name = kind.string();
  if (name == "sphere") {
    c.only_keys({"generate", "triangles", "radius", "diameter", "volume", "uv", "repair", "remesh"});
    mesh.kind = MeshSource::Kind::sphere;
    mesh.radius = c.required("radius").number_greater_than(0.0);
  } else if (name == "rbc") {
    c.only_keys({"generate", "triangles", "diameter", "volume", "uv", "repair", "remesh"});
    mesh.kind = MeshSource::Kind::rbc;
  } else if (name == "box") {
    // A box is its 12 triangles: no count to choose.
    c.only_keys({"generate", "size", "uv", "repair", "remesh"});
    mesh.kind = MeshSource::Kind::box;
    const JsonCursor size = c.required("size");
    mesh.box_size = size.vec3();
    for (int a = 0; a < 3; ++a)
      if (!(mesh.box_size[a] > 0.0)) size.fail("each side must be > 0 Å, got " + size.shown());
    parse_mesh_size_and_uvs(c, mesh);
    return mesh;
  } else {
    kind.fail("expected \"sphere\", \"rbc\" or \"box\", got " + kind.shown());
  }
  mesh.triangles = static_cast<int>(c.required("triangles").integer_between(1, max_triangles));
  parse_mesh_size_and_uvs(c, mesh);
  return mesh;
}

CompartmentDescription parse_compartment(const std::string& name, const JsonCursor& c,
                                         const Defined<MembraneDescription>& membranes,
                                         const Defined<SolubleDescription>& solubles, const std::filesystem::path& folder) {
  c.only_keys({"mesh", "membrane", "soluble", "scale"});
  CompartmentDescription comp;
  comp.name = name;
  comp.mesh = parse_mesh(c.required("mesh"), folder);
  if (const auto m = c.optional("membrane")) comp.membrane = resolve(*m, membranes, "membrane");
  if (const auto s = c.optional("soluble")) comp.soluble = resolve(*s, solubles, "soluble");
  if (!comp.membrane && !comp.soluble) c.fail("a compartment needs a \"membrane\", a \"soluble\" or both");
  if (const auto scale = c.optional("scale")) {
    if (comp.mesh.diameter || comp.mesh.volume) scale->fail("give the mesh a \"scale\" or a \"diameter\"/\"volume\", not both");
    comp.scale = scale->number_greater_than(0.0);
  }
  return comp;
}

InstanceEntry parse_instance(const JsonCursor& c, std::size_t index, std::uint64_t scene_seed,
                             const Defined<CompartmentDescription>& compartments) {
  const bool random = c.has("count") || c.has("box") || c.has("seed") || c.has("min_gap");
  if (!random) {
    c.only_keys({"compartment", "transform", "matrix"});
    ExplicitInstance e;
    e.compartment = resolve(c.required("compartment"), compartments, "compartment");
    e.transform = parse_placement_transform(c);
    return e;
  }
  c.only_keys({"compartment", "count", "box", "seed", "min_gap"});
  RandomPlacement r;
  r.compartment = resolve(c.required("compartment"), compartments, "compartment");
  r.count = static_cast<int>(c.required("count").integer_between(1, max_copies_per_placement));
  r.box = parse_box(c.required("box"));
  r.seed = c.has("seed") ? c.required("seed").unsigned_integer() : derive_placement_seed(scene_seed, index);
  if (const auto gap = c.optional("min_gap")) r.min_gap = gap->number_at_least(0.0);
  return r;
}

// "medium": {"soluble": name, "region": [[x, y, z], [x, y, z]]} or {"soluble": name, "margin": Å}.
MediumDescription parse_medium(const JsonCursor& c, const Defined<SolubleDescription>& solubles) {
  c.only_keys({"soluble", "region", "margin"});
  MediumDescription m;
  m.soluble = resolve(c.required("soluble"), solubles, "soluble");
  if (c.has("region") && c.has("margin"))
    c.fail("give either \"region\" (the box the medium fills) or \"margin\" (how far it reaches beyond the instances), not both");
  if (const auto region = c.optional("region")) m.region = parse_box(*region);
  if (const auto margin = c.optional("margin")) m.margin = margin->number_at_least(0.0);
  return m;
}

// Calls parse(name, value) for every member of the optional named map `key`, in file order.
template <class Parse>
void for_each_named(const JsonCursor& root, const char* key, Parse parse) {
  const auto map = root.optional(key);
  if (!map) return;
  for (const auto& [name, value] : map->members()) {
    check_name_length(*map, name);
    check_name(value, name);
    parse(name, value);
  }
}

}  // namespace

SceneDescription parse_scene_description(const Json& document, const std::filesystem::path& scene_file) {
  const std::string file = scene_file.string();
  const std::filesystem::path folder = scene_file.parent_path();
  const JsonCursor root(document, file);
  root.only_keys({"format", "version", "description", "seed", "molecules", "membranes", "solubles", "compartments",
                  "instances", "medium", "effects", "camera"});

  const JsonCursor format = root.required("format");
  if (format.string() != scene_format_marker)
    format.fail(std::string("expected \"") + scene_format_marker + "\", got " + format.shown());
  const JsonCursor version = root.required("version");
  if (version.integer_between(1, 1'000'000) != scene_format_version)
    version.fail("unsupported version " + version.shown() + "; this program reads version " +
                 std::to_string(scene_format_version));
  if (const auto description = root.optional("description")) description->string();

  SceneDescription scene;
  scene.source = scene_file;
  if (const auto seed = root.optional("seed")) scene.seed = seed->unsigned_integer();
  for_each_named(root, "molecules", [&](const std::string& name, const JsonCursor& c) {
    scene.molecules.push_back(parse_molecule(name, c, folder));
  });
  const Defined molecules(scene.molecules);
  for_each_named(root, "membranes", [&](const std::string& name, const JsonCursor& c) {
    scene.membranes.push_back(parse_membrane(name, c, molecules, folder));
  });
  for_each_named(root, "solubles", [&](const std::string& name, const JsonCursor& c) {
    scene.solubles.push_back(parse_soluble(name, c, molecules));
  });
  const Defined membranes(scene.membranes);
  const Defined solubles(scene.solubles);
  if (root.required("compartments").members().empty()) root.required("compartments").fail("expected at least one compartment");
  for_each_named(root, "compartments", [&](const std::string& name, const JsonCursor& c) {
    scene.compartments.push_back(parse_compartment(name, c, membranes, solubles, folder));
  });
  const Defined compartments(scene.compartments);
  const auto instances = root.required("instances").elements(1);
  for (std::size_t i = 0; i < instances.size(); ++i)
    scene.instances.push_back(parse_instance(instances[i], i, scene.seed, compartments));
  if (const auto medium = root.optional("medium")) scene.medium = parse_medium(*medium, solubles);
  if (const auto effects = root.optional("effects")) scene.effects = parse_effects(*effects, expanded_instance_count(scene));
  if (const auto camera = root.optional("camera")) scene.camera = parse_camera(*camera);
  return scene;
}

SceneDescription load_scene_description(const std::filesystem::path& scene_file) {
  return parse_scene_description(read_json_file(scene_file), scene_file);
}

}  // namespace nano::scene
