#include "runtime/render/pick_info.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <stdexcept>

namespace nano::render {
namespace {

// Thrown inside describe_hit only; becomes {"hit": true, "error": ...}.
struct BadHit : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class T>
const T& at(std::span<const T> records, std::uint64_t index, const char* section, const char* what) {
  if (index >= records.size())
    throw BadHit(std::string(what) + " " + std::to_string(index) + " is out of range: section " + section + " has " +
                 std::to_string(records.size()) + " record(s)");
  return records[index];
}

template <std::size_t N>
std::string fixed_text(const char (&field)[N]) {
  return std::string(field, strnlen(field, N));
}

// (0, 0) is "no string"; a reference past the section reads as none rather than failing the pick:
// names are decoration, the ids are what must be right.
std::string string_at(const format::Package& package, std::uint32_t offset, std::uint32_t length) {
  const auto strings = package.records<format::SectionKind::strings>();
  if (length == 0 || std::uint64_t(offset) + length > strings.size()) return {};
  return std::string(strings.data() + offset, length);
}

std::uint32_t wrap(std::int64_t a, std::uint32_t n) { return std::uint32_t(((a % n) + n) % n); }

// The Wang tile (absolute index in tiles2d / tiles3d) the recipe puts at `cell`.
std::uint32_t recipe_tile(const format::Package& package, std::uint32_t recipe_index, glm::ivec3 cell) {
  const gpu::Recipe& r = at(package.records<format::SectionKind::recipes>(), recipe_index, "recipes", "recipe");
  if (r.dims.x == 0 || r.dims.y == 0 || r.dims.z == 0) throw BadHit("recipe " + std::to_string(recipe_index) + " is empty");
  const std::uint64_t slot =
      wrap(cell.x, r.dims.x) + std::uint64_t(r.dims.x) * (wrap(cell.y, r.dims.y) + std::uint64_t(r.dims.y) * wrap(cell.z, r.dims.z));
  return at(package.records<format::SectionKind::recipe_indices>(), std::uint64_t(r.first_index) + slot, "recipe_indices",
            "recipe entry");
}

template <class Tile>
const gpu::MoleculeInstance& tile_instance(const format::Package& package, const Tile& tile, std::uint32_t instance,
                                           const char* tile_name) {
  if (instance >= tile.instance_count)
    throw BadHit("copy " + std::to_string(instance) + " is out of range: its Wang " + tile_name + " holds " +
                 std::to_string(tile.instance_count) + " molecule(s)");
  return at(package.records<format::SectionKind::instances>(), std::uint64_t(tile.first_instance) + instance, "instances",
            "instance");
}

// The box (i, j, k) a core or medium hit names, inside `grid` of `dims` boxes and matching its
// linear index.
glm::ivec3 hit_box(const gpu::PixelHit& hit, const glm::uvec3& dims, const char* grid) {
  const glm::ivec3 ijk(hit.cell);
  if (ijk.x < 0 || ijk.y < 0 || ijk.z < 0 || std::uint32_t(ijk.x) >= dims.x || std::uint32_t(ijk.y) >= dims.y ||
      std::uint32_t(ijk.z) >= dims.z)
    throw BadHit("box (" + std::to_string(ijk.x) + ", " + std::to_string(ijk.y) + ", " + std::to_string(ijk.z) + ") lies outside " +
                 grid);
  if (hit.element != ijk.x + std::uint64_t(dims.x) * (ijk.y + std::uint64_t(dims.y) * ijk.z))
    throw BadHit("box index " + std::to_string(hit.element) + " is not the linear index of its (i, j, k)");
  return ijk;
}

// The answer, once the copy the ids name is known: it must hold a molecule of the atom's type (a
// check that the ids agree with each other, not only that each is in range).
nlohmann::json finish(const format::Package& package, const gpu::PixelHit& hit, std::uint32_t type, const gpu::MoleculeType& molecule,
                      nlohmann::json atom, nlohmann::json owner, nlohmann::json placement, const gpu::MoleculeInstance& copy) {
  if (copy.molecule_type != type)
    throw BadHit("atom " + std::to_string(hit.atom) + " belongs to molecule type " + std::to_string(type) +
                 " but the copy the ids name is of type " + std::to_string(copy.molecule_type));
  placement["copy"] = hit.instance;
  placement["copy_number"] = (std::uint64_t(hit.copy_number_hi) << 32) | hit.copy_number_lo;
  nlohmann::json m{{"type", type}, {"name", string_at(package, molecule.name_offset, molecule.name_length)},
                   {"source", string_at(package, molecule.source_offset, molecule.source_length)}};
  return {{"hit", true},
          {"depth", hit.depth},
          {"atom", std::move(atom)},
          {"molecule", std::move(m)},
          {"compartment_instance", std::move(owner)},
          {"placement", std::move(placement)}};
}

nlohmann::json describe(const format::Package& package, const gpu::PixelHit& hit) {
  if (!std::isfinite(hit.depth) || hit.depth < 0) throw BadHit("depth " + std::to_string(hit.depth) + " is not a distance");

  const gpu::Atom& atom = at(package.records<format::SectionKind::atoms>(), hit.atom, "atoms", "atom");
  const auto molecules = package.records<format::SectionKind::molecules>();
  std::uint32_t type = gpu::kNoHit;
  for (std::uint32_t m = 0; m < molecules.size() && type == gpu::kNoHit; ++m)
    if (hit.atom >= molecules[m].first_atom && hit.atom - molecules[m].first_atom < molecules[m].atom_count) type = m;
  if (type == gpu::kNoHit) throw BadHit("atom " + std::to_string(hit.atom) + " belongs to no molecule type");
  const gpu::MoleculeType& molecule = molecules[type];

  nlohmann::json a{{"index", hit.atom},
                   {"index_in_molecule", hit.atom - molecule.first_atom},
                   {"position", {atom.centre_radius.x, atom.centre_radius.y, atom.centre_radius.z}},
                   {"radius", atom.centre_radius.w}};
  const auto infos = package.records<format::SectionKind::atom_info>();
  if (!infos.empty()) {  // optional section; when present it is parallel to atoms
    const format::AtomInfo& info = at(infos, hit.atom, "atom_info", "atom");
    a["name"] = fixed_text(info.atom_name);
    a["element"] = fixed_text(info.element);
    a["chain"] = fixed_text(info.chain);
    a["residue_name"] = fixed_text(info.residue_name);
    a["residue_number"] = info.residue_number;
    if (info.insertion_code != '\0') a["insertion_code"] = std::string(1, info.insertion_code);
    if (info.alt_location != '\0') a["alt_location"] = std::string(1, info.alt_location);
  }

  nlohmann::json placement;
  const gpu::MoleculeInstance* copy = nullptr;
  if (hit.kind == gpu::NANO_KIND_MEDIUM) {
    // The medium's copies belong to no compartment instance: the region box and its cube name them.
    const auto media = package.records<format::SectionKind::medium>();
    if (media.empty()) throw BadHit("medium hit in a package without a medium");
    if (hit.compartment_instance != gpu::NANO_MEDIUM_OWNER)
      throw BadHit("medium hit naming compartment instance " + std::to_string(hit.compartment_instance));
    const glm::ivec3 ijk = hit_box(hit, glm::uvec3(media[0].boxes), "the medium's region");
    const std::uint32_t tile_index = recipe_tile(package, media[0].boxes.w, ijk);
    const gpu::Tile3D& tile = at(package.records<format::SectionKind::tiles3d>(), tile_index, "tiles3d", "Wang cube");
    copy = &tile_instance(package, tile, hit.instance, "cube");
    placement = {{"kind", "medium"}, {"box", hit.element}, {"box_ijk", {ijk.x, ijk.y, ijk.z}}, {"wang_cube", tile_index}};
    return finish(package, hit, type, molecule, std::move(a), nlohmann::json{{"medium", true}}, std::move(placement), *copy);
  }
  const gpu::CompartmentInstance& ci = at(package.records<format::SectionKind::compartment_instances>(),
                                          hit.compartment_instance, "compartment_instances", "compartment instance");
  const gpu::Compartment& c =
      at(package.records<format::SectionKind::compartments>(), ci.compartment, "compartments", "compartment");
  nlohmann::json compartment{{"index", hit.compartment_instance}, {"compartment", ci.compartment}};
  if (const std::string name = string_at(package, c.name_offset, c.name_length); !name.empty())
    compartment["name"] = name;

  if (hit.kind == 0) {
    if (c.membrane_recipe == gpu::NANO_NO_INDEX) throw BadHit("membrane hit in a compartment without a membrane");
    const gpu::Mesh& mesh = at(package.records<format::SectionKind::meshes>(), c.mesh, "meshes", "mesh");
    if (hit.element < mesh.first_triangle || hit.element - mesh.first_triangle >= mesh.triangle_count)
      throw BadHit("triangle " + std::to_string(hit.element) + " is not one of the compartment's mesh");
    const std::uint32_t tile_index = recipe_tile(package, c.membrane_recipe, glm::ivec3(hit.cell.x, hit.cell.y, 0));
    const gpu::Tile2D& tile = at(package.records<format::SectionKind::tiles2d>(), tile_index, "tiles2d", "Wang square");
    copy = &tile_instance(package, tile, hit.instance, "square");
    placement = {{"kind", "membrane"}, {"triangle", hit.element}, {"tile", {hit.cell.x, hit.cell.y}},
                 {"wang_square", tile_index}};
  } else if (hit.kind == 1) {
    if (c.soluble_recipe == gpu::NANO_NO_INDEX) throw BadHit("core hit in a compartment without a core grid");
    const glm::ivec3 ijk = hit_box(hit, glm::uvec3(c.grid_dims), "the core grid");
    const std::uint32_t tile_index = recipe_tile(package, c.soluble_recipe, ijk);
    const gpu::Tile3D& tile = at(package.records<format::SectionKind::tiles3d>(), tile_index, "tiles3d", "Wang cube");
    copy = &tile_instance(package, tile, hit.instance, "cube");
    placement = {{"kind", "core"}, {"box", hit.element}, {"box_ijk", {ijk.x, ijk.y, ijk.z}}, {"wang_cube", tile_index}};
  } else {
    throw BadHit("kind " + std::to_string(hit.kind) + " is neither 0 (membrane), 1 (core) nor 2 (medium)");
  }
  return finish(package, hit, type, molecule, std::move(a), std::move(compartment), std::move(placement), *copy);
}
}  // namespace

nlohmann::json describe_hit(const format::Package& package, const gpu::PixelHit& hit) {
  if (hit.atom == gpu::kNoHit) return {{"hit", false}};
  try {
    return describe(package, hit);
  } catch (const BadHit& e) {
    return {{"hit", true}, {"error", e.what()}};
  }
}

std::string describe_hit_text(const nlohmann::json& d) {
  if (!d.value("hit", false)) return "background";
  if (d.contains("error")) return "invalid hit: " + d["error"].get<std::string>();
  const nlohmann::json &a = d["atom"], &m = d["molecule"], &ci = d["compartment_instance"], &p = d["placement"];
  std::string text;
  if (a.contains("name")) {
    text = "atom " + a["name"].get<std::string>() + " (" + a["element"].get<std::string>() + ") of " +
           a["residue_name"].get<std::string>() + " " + std::to_string(a["residue_number"].get<int>()) +
           a.value("insertion_code", "") + ", chain " + a["chain"].get<std::string>();
    if (a.contains("alt_location")) text += ", alt. location " + a["alt_location"].get<std::string>();
  } else {
    text = "atom " + std::to_string(a["index"].get<std::uint32_t>());
  }
  char line[160];
  std::snprintf(line, sizeof line, "; radius %.2f Å\n", a["radius"].get<double>());
  text += line;
  text += "molecule " + m["name"].get<std::string>() + " (type " + std::to_string(m["type"].get<std::uint32_t>());
  if (!m["source"].get<std::string>().empty()) text += ", from " + m["source"].get<std::string>();
  text += ")\n";
  if (ci.value("medium", false))
    text += "the medium, between the compartments; ";
  else
    text += "compartment " + ci.value("name", std::to_string(ci["compartment"].get<std::uint32_t>())) +
            ", instance " + std::to_string(ci["index"].get<std::uint32_t>()) + "; ";
  if (p["kind"] == "membrane")
    text += "membrane, triangle " + std::to_string(p["triangle"].get<std::uint32_t>()) + ", tile (" +
            std::to_string(p["tile"][0].get<int>()) + ", " + std::to_string(p["tile"][1].get<int>()) + ")";
  else
    text += p["kind"].get<std::string>() + ", box (" + std::to_string(p["box_ijk"][0].get<int>()) + ", " + std::to_string(p["box_ijk"][1].get<int>()) +
            ", " + std::to_string(p["box_ijk"][2].get<int>()) + ")";
  text += ", copy " + std::to_string(p["copy"].get<std::uint32_t>()) + "\n";
  std::snprintf(line, sizeof line, "depth %.2f Å, copy number %llu", d["depth"].get<double>(),
                (unsigned long long)p["copy_number"].get<std::uint64_t>());
  return text + line;
}

}  // namespace nano::render
