#pragma once
// A compartment's proxy mesh in compartment space, through stages each run once on the output of the
// one before: read (or generated) → repaired (when the scene asks) → sized → prepared for its
// membrane and judged (mesh/membrane_fit.hpp: remeshed when it needs it) → charted (UVs made when it
// has none usable) → checked. An unusable mesh stops the bake with every problem listed, naming the
// file. `nanobake check-mesh --diameter` runs the same stages and stops before the shells.
#include <functional>
#include <optional>
#include <string>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/membrane_fit.hpp"
#include "bake/mesh/mesh_remesh.hpp"
#include "bake/mesh/mesh_repair.hpp"
#include "bake/mesh/uv_charts.hpp"
#include "bake/mesh/proxy_mesh.hpp"
#include "bake/scene/scene_description.hpp"
#include "bake/scene/scene_feasibility.hpp"

namespace nano::scene_bake {

struct CompartmentMesh {
  mesh::ProxyMesh mesh;     // compartment space (scale applied)
  mesh::MeshReport report;  // check-mesh report of the scaled mesh
  std::string origin;       // file name or "generated sphere (N triangles, radius R)"
  double scale = 1.0;       // compartment space per mesh unit: units × scale, diameter or volume
  std::optional<mesh::ChartAtlas> charts;  // when the baker made the UVs
  std::optional<mesh::RepairReport> repair;  // when the scene asked for "repair"
  std::optional<mesh::RemeshReport> remesh;  // when the baker remeshed it for its membrane
  double bilayer_thickness = 0.0;           // Å, of the membrane that lines it (0: none)
  double thinnest_wall = 0.0;               // Å, where a membrane lines it (mesh::MembraneFit)
  double narrowest_gap = 0.0;               // Å, likewise
  std::string uv_origin;    // "from the mesh" or why the baker made them
  bool on_storage_grids = false;  // put_on_storage_grids succeeded: Draco can store it exactly
  std::string storage;      // what put_on_storage_grids did, or why it left the mesh exact
};

// The last stage load_compartment_mesh runs: the judgement (check-mesh), or the charts (the bake).
enum class MeshStage { judged, charted };

// Reads or generates the mesh, scales it (units, then the compartment's scale or the mesh's target
// diameter or volume), remeshes it for a membrane `bilayer_thickness` Å thick when its creases or
// slivers need it or the scene asks (not for a compartment without membrane: nullopt), makes UVs when
// the mesh has none usable (or the scene asks) and checks it. Throws InputError naming the mesh (and
// the compartment) with all problems when unusable.
// `check_size`, when given, sees the mesh at its final size before any heavy work on it (repair
// excepted): the baker's feasibility checks refuse a mesh too large for float coordinates there.
CompartmentMesh load_compartment_mesh(const scene::CompartmentDescription& compartment,
                                      std::optional<double> bilayer_thickness = std::nullopt,
                                      const std::function<void(const mesh::ProxyMesh&)>& check_size = {},
                                      MeshStage until = MeshStage::charted);

// Area, enclosed volume and reach from the origin of a mesh, for the feasibility checks.
scene::CompartmentMeasure measure_compartment(const mesh::ProxyMesh& mesh);

// Moves the mesh onto the grids of Draco mesh sections (mesh_packing.hpp: on_storage_grids) if the
// moved mesh still passes every check; otherwise leaves it exact (then zstd stores it) and says why.
void put_on_storage_grids(CompartmentMesh& mesh);

// Positions multiplied by `scale` (> 0); UVs and normals unchanged.
void scale_mesh(mesh::ProxyMesh& mesh, double scale);

}  // namespace nano::scene_bake
