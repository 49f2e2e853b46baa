// v2 recipes (format_version 2.0–2.1): `objects` are types (with `inherit`), `composition` entries
// place them; the one entry nobody lists is the outside, an entry with `regions` is a container.
#include <map>
#include <set>

#include "bake/cellpack/recipe_formats.hpp"
#include "bake/cellpack/recipe_values.hpp"

namespace nano::cellpack {
namespace {

// Nested objects merge, the child's values win (cellPACK's deep_merge for `inherit` and for a
// composition item over its object).
void deep_merge(Json& base, const Json& child) {
  for (const auto& [key, value] : child.items()) {
    if (value.is_object() && base.contains(key) && base[key].is_object()) deep_merge(base[key], value);
    else base[key] = value;
  }
}

class V2Reader {
public:
  V2Reader(const JsonCursor& root, Recipe& recipe) : root_(root), recipe_(recipe) {}

  void read() {
    if (const auto objects = root_.optional("objects"))
      for (const auto& [name, c] : objects->members()) objects_.emplace(name, c);
    const JsonCursor composition = root_.required("composition");
    for (const auto& [name, c] : composition.members()) entries_.emplace(name, c);
    const std::string root_name = find_root(composition);
    walk(root_name, kOutside, 0);
  }

private:
  // The merged object `name` (its `inherit` chain resolved); a cycle or an unknown name is refused.
  Json object(const std::string& name, const JsonCursor& asked_by, std::set<std::string>& seen) {
    const auto it = objects_.find(name);
    if (it == objects_.end()) asked_by.fail("unknown object '" + name + "'");
    if (!seen.insert(name).second) asked_by.fail("objects inherit in a cycle through '" + name + "'");
    if (!it->second.json().is_object()) it->second.fail("expected an object, got " + it->second.shown());
    Json merged = Json::object();
    if (const auto parent = it->second.optional("inherit"))
      merged = object(parent->string(), *parent, seen);
    deep_merge(merged, it->second.json());
    return merged;
  }

  std::string find_root(const JsonCursor& composition) {
    std::set<std::string> listed;
    for (const auto& [name, entry] : entries_)
      for (const auto& [region, items] : regions_of(entry))
        for (const JsonCursor& item : items.elements())
          if (item.json().is_string()) {
            if (!entries_.count(item.string())) item.fail("unknown composition entry '" + item.string() + "'");
            listed.insert(item.string());
          }
    std::vector<std::string> roots;
    for (const auto& [name, entry] : entries_)
      if (!listed.count(name)) roots.push_back(name);
    if (roots.size() != 1)
      composition.fail("expected exactly one entry that no other lists (the outside), got " + std::to_string(roots.size()));
    return roots[0];
  }

  static std::vector<std::pair<std::string, JsonCursor>> regions_of(const JsonCursor& entry) {
    if (!entry.json().is_object()) entry.fail("expected a composition entry object, got " + entry.shown());
    const std::optional<JsonCursor> regions = entry.optional("regions");
    if (!regions || regions->json().is_null()) return {};
    return regions->members();
  }

  // Containers by their index in recipe_.compartments (the list grows while they are walked).
  static constexpr std::size_t kOutside = std::size_t(-1);

  void walk(const std::string& name, std::size_t container, int depth) {
    const JsonCursor& entry = entries_.at(name);
    if (depth > 16) entry.fail("containers nested more than 16 deep");
    for (const auto& [region, items] : regions_of(entry)) {
      if (region != "interior" && region != "surface" && region != "inner_leaflet" && region != "outer_leaflet")
        items.fail("unknown region '" + region + "' (known: interior, surface, inner_leaflet, outer_leaflet)");
      for (const JsonCursor& item : items.elements()) place(item, region, container, depth);
    }
  }

  void place(const JsonCursor& item, const std::string& region, std::size_t container, int depth) {
    if (item.json().is_string() && !regions_of(entries_.at(item.string())).empty()) {
      add_container(item.string(), entries_.at(item.string()), container, depth);
      return;
    }
    Ingredient in = item.json().is_string() ? ingredient(entries_.at(item.string()), item.string())
                                            : ingredient(item, read_name(item.optional("object")));
    if (container == kOutside) {
      recipe_.outside.push_back(std::move(in));
      return;
    }
    Compartment& c = recipe_.compartments[container];
    std::vector<Ingredient>& list = region == "interior" ? c.interior : c.surface;
    list.push_back(std::move(in));
    if (region != "interior" && region != "surface")
      list.back().not_carried.push_back("region " + region + " (read as the surface: cellPACK packs neither leaflet)");
  }

  void add_container(const std::string& name, const JsonCursor& entry, std::size_t parent, int depth) {
    Compartment comp;
    comp.id = name;
    comp.where = entry.file() + ":" + entry.path();
    comp.parent = parent == kOutside ? "" : recipe_.compartments[parent].id;
    if (const auto object_name = entry.optional("object")) {
      std::set<std::string> seen;
      const Json merged = object(object_name->string(), *object_name, seen);
      const std::string label = entry.file() + " (objects." + object_name->string() + ")";
      const JsonCursor o(merged, label);
      const std::string type = read_name(o.optional("type"));
      if (type == "single_sphere") {
        comp.geometry = Compartment::Geometry::sphere;
        comp.radius = lenient_number(o.required("radius"));
        if (!(comp.radius > 0.0)) o.fail("expected a sphere radius > 0 Å");
      } else if (type == "mesh") {
        const JsonCursor mesh = o.required("representations").required("mesh");
        comp.geometry = Compartment::Geometry::mesh;
        comp.mesh_file = read_name(mesh.optional("name"));
        if (comp.mesh_file.empty()) mesh.fail("a mesh container needs its mesh file's name");
      } else {
        o.fail("a container's object must be a single_sphere or a mesh, got type '" + type + "'");
      }
    }
    recipe_.compartments.push_back(std::move(comp));
    walk(name, recipe_.compartments.size() - 1, depth + 1);
  }

  // A composition entry or item over its object: the item's own values win.
  Ingredient ingredient(const JsonCursor& item, const std::string& id) {
    const std::optional<JsonCursor> object_name = item.optional("object");
    if (!object_name) item.fail("an ingredient needs its `object`");
    std::set<std::string> seen;
    Json merged = object(object_name->string(), *object_name, seen);
    deep_merge(merged, item.json());
    const std::string label = item.file() + " (" + item.path() + " over objects." + object_name->string() + ")";
    const JsonCursor c(merged, label);
    Ingredient in;
    in.id = id;
    in.where = item.file() + ":" + item.path();
    in.file = item.file();
    const std::optional<JsonCursor> atomic = c.has("representations") ? c.required("representations").optional("atomic") : std::nullopt;
    if (atomic) in.structure = atomic->has("id") ? read_name(atomic->optional("id")) : read_name(atomic->optional("name"));
    in.molarity = read_molarity(c.optional("molarity"));
    in.count = read_count(c.optional("count"));
    in.principal_vector = read_optional_vec3(c.optional("principal_vector"));
    in.offset = read_optional_vec3(c.optional("offset"));
    in.colour = read_colour(c.optional("color"));
    if (const auto r = c.optional("radius"); r && !r->json().is_null()) in.encapsulating_radius = lenient_number(*r);
    const std::optional<JsonCursor> packing = c.has("representations") ? c.required("representations").optional("packing") : std::nullopt;
    if (packing) {
      // {"path": "github:collisionTrees", "name": "X.sph"}: a file of cellPACK's database, found like
      // an include (--server); "default" or no path: beside the recipe.
      in.sphere_file = read_name(packing->optional("name"));
      const std::string path = read_name(packing->optional("path"));
      if (!in.sphere_file.empty() && !path.empty() && path != "default") in.sphere_file = path + "/" + in.sphere_file;
      in.spheres = read_inline_spheres(packing->optional("radii"), packing->optional("positions"));
    }
    in.type = read_name(c.optional("type"));
    const bool partners = c.has("partners") && !c.required("partners").json().empty();
    std::string gradient = c.has("gradient") && c.required("gradient").json().is_string() ? read_name(c.optional("gradient")) : "";
    if (c.has("gradient") && c.required("gradient").json().is_array()) gradient = c.required("gradient").json().dump();
    note_not_carried(in, in.type, gradient, partners, read_name(c.optional("packing_mode")));
    if (c.has("count_options") || c.has("size_options"))
      in.not_carried.push_back("count_options/size_options (a drawn count or size: the count as given is used)");
    return in;
  }

  const JsonCursor& root_;
  Recipe& recipe_;
  std::map<std::string, JsonCursor> objects_;
  std::map<std::string, JsonCursor> entries_;
};

}  // namespace

void read_v2(const JsonCursor& root, Recipe& recipe) {
  recipe.format = RecipeFormat::v2;
  recipe.name = read_name(root.optional("name"));
  recipe.version = read_name(root.optional("format_version"));
  if (const auto box = root.optional("bounding_box"); box && !box->json().is_null()) {
    const std::vector<JsonCursor> corners = box->elements(2);
    recipe.box_min = read_optional_vec3(corners[0]);
    recipe.box_max = read_optional_vec3(corners[1]);
  }
  if (const auto g = root.optional("gradients"); g && !g->json().empty())
    recipe.not_carried.push_back("gradients (" + std::to_string(g->json().size()) + "): copies are spread uniformly");
  V2Reader(root, recipe).read();
}

}  // namespace nano::cellpack
