#pragma once
// A cellPACK recipe as its file says it, before anything is mapped onto a Nanouniverse scene: the
// regions it fills (the space outside every compartment, each compartment's surface and interior)
// and, per region, the ingredients with what they ask for. Both formats users have read into this
// one model: v1 (autoPACK recipe versions 1.0–1.1: `cytoplasme`, `compartments`, `include`) and v2
// (format_version 2.0–2.1: `objects` with `inherit`, `composition` with `regions`).
// Units are cellPACK's: Å, mol/L. What the model cannot hold is named in `not_carried`, never
// dropped silently.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace nano::cellpack {

enum class RecipeFormat { v1, v2 };

struct Ingredient {
  std::string id;                 // v1: its key in the ingredient list; v2: the composition name or object
  std::string where;              // "FILE:KEY.PATH" of its definition, for reports and errors
  std::string file;               // FILE: the recipe or the include that defines it (its own files are beside it)
  std::string structure;          // PDB id or structure file name as written ("" when the recipe gives none)
  double molarity = 0;            // mol/L; on a surface cellPACK reads it per Å² (molarity · 6.022e-4 per Å²)
  std::uint64_t count = 0;        // v1 nbMol, v2 count: copies added to what the molarity asks for
  std::optional<glm::dvec3> principal_vector;  // the molecule axis cellPACK turns onto the surface normal
  std::optional<glm::dvec3> offset;            // Å, molecule frame (Mesoscope convention)
  std::optional<glm::dvec3> colour;            // linear 0–1 (0–255 values are scaled)
  double encapsulating_radius = 0;             // Å; 0: not given
  std::string sphere_file;                     // packing sphere tree (.sph) as written; "" none
  std::vector<glm::dvec4> spheres;             // inline packing spheres (x, y, z, r), Å, finest level
  std::string type;                            // cellPACK's type: MultiSphere, SingleSphere, Grow, ...
  std::vector<std::string> not_carried;        // what this ingredient asks for that the model does not hold
};

struct Compartment {
  enum class Geometry { none, sphere, mesh };
  std::string id;
  std::string where;
  Geometry geometry = Geometry::none;
  double radius = 0;                // Å (sphere)
  glm::dvec3 centre{0.0};           // Å (sphere)
  std::string mesh_file;            // as written (mesh): resolved by the importer
  std::string parent;               // v2: the container it was listed in ("" the outside); v1 has no nesting
  std::vector<Ingredient> surface;
  std::vector<Ingredient> interior;
};

struct Recipe {
  RecipeFormat format = RecipeFormat::v1;
  std::string file;                 // the recipe file as given
  std::string name;
  std::string version;              // v1 recipe.version; v2 format_version
  std::optional<glm::dvec3> box_min;  // bounding box (Å), when the recipe gives one
  std::optional<glm::dvec3> box_max;
  std::vector<Ingredient> outside;  // v1 cytoplasme, v2 the root's regions: between the compartments
  std::vector<Compartment> compartments;
  std::vector<std::string> not_carried;  // recipe-level: gradients, options that only drive cellPACK's packer
};

}  // namespace nano::cellpack
