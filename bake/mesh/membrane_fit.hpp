#pragma once
// Will a bilayer fit this mesh? The one judgement the baker and check-mesh share, made on the surface
// the baker will shell: the mesh is remeshed for the membrane first when it needs it (mesh_remesh.hpp),
// then measured where a bilayer `thickness` Å thick cannot follow it — walls thinner than the bilayer,
// gaps narrower than it, creases the remeshing could not round, the surface passing through itself.
// Tight triangles that touch are one place. A place that only a size far beyond the one asked could
// cure (a near-contact of two sheets, a razor-thin rim) is a defect of the mesh, named where it is;
// otherwise the smallest uniform scale at which the mesh takes the bilayer is found and checked by
// preparing and judging the mesh again at that size (up to kPlausibleGrowth; beyond, none is named).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_remesh.hpp"
#include "bake/mesh/proxy_mesh.hpp"
#include "common/error.hpp"

namespace nano::mesh {

// A 90° crease needs a wall this many bilayers thick behind it to be rounded for the bilayer
// (measured on the voxel plate with two holes and a POPC bilayer 62 Å thick: walls of 3.8 bilayers
// left one triangle no prism, 5.1 baked); gentler creases need less, as 1 − cos(θ/2).
inline constexpr double kCreaseWallAt90 = 5.0;
// A POPC bilayer, atom surface to atom surface (data/structures/popc_bilayer.pdb.gz, the bundled
// scenes' lipid; a test measures it): what check-mesh judges a mesh against when told nothing else,
// and what a membrane without lipids of its own lines its mesh with.
inline constexpr double kDefaultBilayerThickness = 61.8;
// The surface may bend no tighter than this many bilayer thicknesses of radius (the remeshing rounds
// creases over 1.5; tighter, the inner leaflet folds onto itself).
inline constexpr double kMinBendBilayers = 0.5;
// A place needing the mesh this many times larger than asked is a defect of the mesh, not a size.
inline constexpr double kPlausibleGrowth = 8.0;
// Rounding a mesh's creases for the bilayer may take at most this share of its area: more, and the
// membrane would line a blob, not the user's shape (a 150 Å cube under a 40 Å bilayer loses 47 %).
inline constexpr double kMaxRoundingAreaLoss = 0.2;
// Rounds of preparing and judging the mesh again at a larger size before a suggested size is given.
inline constexpr int kSizeChecks = 3;

struct RemeshPolicy {
  enum class Mode { automatic, off, edge } mode = Mode::automatic;
  double edge = 0.0;  // Mode::edge, Å
};

// One place where the bilayer cannot follow the surface: connected tight triangles of the prepared
// mesh, described by the tightest of them.
struct TightFeature {
  glm::dvec3 position{0.0};  // the tightest triangle's centroid, Å
  std::string what;          // "wall", "gap", "bend", "crease", "self-intersection" or "rounding" (the whole mesh)
  double found = 0.0;        // Å: the wall's thickness, the gap's width or the bend's radius there (0: the surface crosses itself);
                             // "rounding": the share of the area the rounding takes
  double needed = 0.0;       // Å ("rounding": kMaxRoundingAreaLoss)
  double crease_degrees = 0.0;  // "crease" only
  std::size_t triangles = 0;    // tight triangles of the place
  bool defect = false;          // no size within kPlausibleGrowth of the one asked cures it
  // The remeshed surface crosses itself here; found and what are then the input's own (a near-contact
  // of two sheets closer than the remeshing's edge, or a wall thinner than it).
  bool crossed_when_remeshed = false;
  double growth() const { return found > 0.0 ? needed / found : INFINITY; }
};

struct MembraneFit {
  std::optional<RemeshReport> remesh;
  std::vector<TightFeature> tight;  // defects first, then tightest (largest growth) first; empty when it fits
  // The smallest uniform scale at which the mesh took the bilayer when prepared and judged again
  // (size_checked), or the estimate from the places found (> 1 when it does not fit now).
  double scale_needed = 1.0;
  bool size_checked = false;
  double largest_scale_tried = 0.0;  // by the size checks (at most kPlausibleGrowth)
  double thinnest_wall = 0.0, narrowest_gap = 0.0;  // Å, over the whole prepared mesh (INFINITY: none)
  bool fits() const { return tight.empty(); }
  bool has_defect() const;
};

// Prepares `mesh` (scaled to its final size; `report` its check-mesh report) for a bilayer
// `thickness` Å thick — remeshed when the policy and its creases or slivers ask, replacing `report` —
// and judges the prepared surface. When it does not fit and no place is a defect, the size that
// works is checked on a copy (kSizeChecks rounds at most). Throws an InputError from `source` (the
// mesh file, and the compartment the scene reads it for) when the mesh has problems besides UVs and
// slivers and would need remeshing (remeshing does not guess at a shape), naming the first; a caller
// that lists them all asks remesh_needed first.
MembraneFit fit_membrane(ProxyMesh& mesh, MeshReport& report, double thickness, const RemeshPolicy& policy,
                         const InputSource& source);

// Why fit_membrane would remesh the mesh (`report`: its check-mesh report) under `policy`, or nullopt.
std::optional<std::string> remesh_needed(const ProxyMesh& mesh, const MeshReport& report, const RemeshPolicy& policy);

// The places (at most `shown`) with where they are — in Å and, with `file_scale` (Å per unit of the
// file) != 1, in the file's own coordinates — and what to do: mend a defect there, or the smallest
// diameter (when the mesh was sized by `diameter`, Å) or scale at which the mesh takes the bilayer.
std::string describe_tight_features(const MembraneFit& fit, double thickness, std::optional<double> diameter,
                                    double file_scale = 1.0, std::size_t shown = 5);

}  // namespace nano::mesh
