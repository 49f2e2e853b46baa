// v1 recipes (autoPACK, recipe versions 1.0–1.1): `cytoplasme` and `compartments` hold ingredient
// lists, inline or by `include`; compartments are meshes (`geom`), spheres or Mesoscope metaballs.
#include <cmath>

#include "bake/cellpack/recipe_formats.hpp"
#include "bake/cellpack/recipe_values.hpp"

namespace nano::cellpack {
namespace {

std::optional<JsonCursor> nested(const JsonCursor& c, std::initializer_list<const char*> keys) {
  std::optional<JsonCursor> at = c;
  for (const char* k : keys) {
    if (!at || !at->json().is_object()) return std::nullopt;
    at = at->optional(k);
  }
  return at;
}

// The fields of one v1 ingredient definition (inline, or the document an include names).
Ingredient read_fields(const JsonCursor& c, std::string id) {
  if (!c.json().is_object()) c.fail("expected an ingredient object, got " + c.shown());
  Ingredient in;
  in.id = std::move(id);
  in.where = c.file() + ":" + c.path();
  in.file = c.file();
  in.structure = read_name(nested(c, {"source", "pdb"}));
  if (in.structure.empty()) in.structure = read_name(c.optional("pdb"));
  in.molarity = read_molarity(c.optional("molarity"));
  in.count = read_count(c.optional("nbMol"));
  in.principal_vector = read_optional_vec3(c.optional("principalVector"));
  in.offset = read_optional_vec3(c.optional("offset"));
  if (!in.offset) in.offset = read_optional_vec3(nested(c, {"source", "transform", "offset"}));
  in.colour = read_colour(c.optional("color"));
  if (const auto r = c.optional("encapsulatingRadius"); r && !r->json().is_null()) {
    in.encapsulating_radius = lenient_number(*r);
    if (!(in.encapsulating_radius >= 0.0)) r->fail("expected a radius >= 0 Å, got " + r->shown());
  }
  in.sphere_file = read_name(c.optional("sphereFile"));
  in.spheres = read_inline_spheres(c.optional("radii"), c.optional("positions"));
  in.type = read_name(c.optional("Type"));
  if (in.type.empty()) in.type = "SingleSphere";
  const std::optional<JsonCursor> partners = c.optional("partners_name");
  const bool has_partners = partners && partners->json().is_array() && !partners->json().empty();
  note_not_carried(in, in.type, read_name(c.optional("gradient")), has_partners, read_name(c.optional("packingMode")));
  return in;
}

Ingredient read_entry(const JsonCursor& c, const std::string& id, RecipeFiles& files) {
  const std::optional<JsonCursor> include = c.json().is_object() ? c.optional("include") : std::nullopt;
  if (!include) return read_fields(c, id);
  std::string file;
  const Json& doc = files.include(*include, file);
  Json merged = doc;
  // A stub's `overwrite` applies on top of the included definition (autoPACK's loader does so).
  if (const auto over = c.optional("overwrite"); over && over->json().is_object())
    for (const auto& [key, value] : over->json().items()) merged[key] = value;
  const std::string name = c.has("overwrite") ? file + " (with " + c.file() + ":" + c.path() + ".overwrite)" : file;
  const JsonCursor definition(merged, name);
  if (!merged.is_object()) definition.fail("expected an ingredient object, got " + definition.shown());
  // An ingredient file defines one ingredient; following its own include would make chains and cycles.
  if (merged.contains("include")) definition.required("include").fail("an included ingredient file includes nothing further");
  return read_fields(definition, id);
}

// An ingredient list: {"KEY": ingredient-or-stub, …} under `ingredients` (a list of them is read too).
std::vector<Ingredient> read_ingredients(const std::optional<JsonCursor>& region, RecipeFiles& files) {
  std::vector<Ingredient> out;
  if (!region || region->json().is_null()) return out;
  const std::optional<JsonCursor> list = region->optional("ingredients");
  if (!list || list->json().is_null()) return out;
  if (list->json().is_array()) {
    for (const JsonCursor& e : list->elements()) out.push_back(read_entry(e, read_name(e.optional("name")), files));
    return out;
  }
  for (const auto& [key, e] : list->members()) out.push_back(read_entry(e, key, files));
  return out;
}

void read_geometry(const JsonCursor& c, Compartment& comp) {
  std::string kind = read_name(c.optional("meshType"));
  if (kind.empty()) kind = read_name(c.optional("geom_type"));
  if (kind.empty()) kind = "file";
  const std::optional<JsonCursor> geom = c.optional("geom");
  if (kind == "file") {
    comp.mesh_file = read_name(geom);
    comp.geometry = comp.mesh_file.empty() ? Compartment::Geometry::none : Compartment::Geometry::mesh;
  } else if (kind == "sphere") {
    const std::optional<JsonCursor> r = geom ? geom->optional("radius") : std::nullopt;
    comp.radius = r ? lenient_number(*r) : 200.0;  // autoPACK's default
    comp.geometry = Compartment::Geometry::sphere;
  } else if (kind == "mb") {  // Mesoscope's metaball: one ball, centre and radius
    const JsonCursor mb = c.required("mb");
    const std::vector<JsonCursor> centre = mb.required("positions").elements(3), radii = mb.required("radii").elements(1);
    comp.centre = glm::dvec3(lenient_number(centre[0]), lenient_number(centre[1]), lenient_number(centre[2]));
    comp.radius = lenient_number(radii[0]);
    comp.geometry = Compartment::Geometry::sphere;
  } else {
    c.fail("unknown compartment geometry '" + kind + "' (known: file, sphere, mb)");
  }
  if (comp.geometry == Compartment::Geometry::sphere && !(comp.radius > 0.0))
    c.fail("expected a sphere radius > 0 Å, got " + std::to_string(comp.radius));
}

}  // namespace

void read_v1(const JsonCursor& root, RecipeFiles& files, Recipe& recipe) {
  recipe.format = RecipeFormat::v1;
  const JsonCursor head = root.required("recipe");
  recipe.name = read_name(head.optional("name"));
  recipe.version = head.has("version") ? head.required("version").json().dump() : "";
  if (const auto box = nested(root, {"options", "boundingBox"}); box && !box->json().is_null()) {
    const std::vector<JsonCursor> corners = box->elements(2);
    // autoPACK writes null into a box it derives from the compartments: then there is none to read.
    const auto known = [](const JsonCursor& c) { return c.json().dump().find("null") == std::string::npos; };
    if (corners.size() == 2 && known(corners[0]) && known(corners[1])) {
      recipe.box_min = read_optional_vec3(corners[0]);
      recipe.box_max = read_optional_vec3(corners[1]);
    }
  }
  if (const auto g = root.optional("gradients"); g && g->json().is_object() && !g->json().empty())
    recipe.not_carried.push_back("gradients (" + std::to_string(g->json().size()) + "): copies are spread uniformly");
  recipe.outside = read_ingredients(root.optional("cytoplasme"), files);
  const std::optional<JsonCursor> comps = root.optional("compartments");
  if (!comps || comps->json().is_null()) return;
  for (const auto& [key, c] : comps->members()) {
    if (key == "include") {
      recipe.not_carried.push_back("compartments.include (compartments copied from another recipe)");
      continue;
    }
    Compartment comp;
    comp.id = key;
    comp.where = c.file() + ":" + c.path();
    read_geometry(c, comp);
    comp.surface = read_ingredients(c.optional("surface"), files);
    comp.interior = read_ingredients(c.optional("interior"), files);
    recipe.compartments.push_back(std::move(comp));
  }
}

}  // namespace nano::cellpack
