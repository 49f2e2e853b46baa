#pragma once
// Will a bilayer fit this mesh? The one judgement the baker and check-mesh share: the mesh is
// remeshed for the membrane when it needs it (mesh_remesh.hpp), then measured where a bilayer
// `thickness` Å thick cannot follow it — walls thinner than the bilayer, gaps narrower than it,
// creases the remeshing could not round — each named by triangle, place and size, with the smallest
// uniform scale at which every one of them would fit.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_remesh.hpp"
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {


// A 90° crease needs a wall this many bilayers thick behind it to be rounded for the bilayer
// (measured on the voxel plate with two holes and a POPC bilayer 62 Å thick: walls of 3.8 bilayers
// left one triangle no prism, 5.1 baked); gentler creases need less, as 1 − cos(θ/2).
inline constexpr double kCreaseWallAt90 = 5.0;

struct RemeshPolicy {
  enum class Mode { automatic, off, edge } mode = Mode::automatic;
  double edge = 0.0;  // Mode::edge, Å
};

struct TightFeature {
  std::uint32_t triangle = 0;
  glm::dvec3 position{0.0};  // the triangle's centroid, Å
  std::string what;          // "wall", "gap" or "crease"
  double found = 0.0;        // Å: the wall's thickness or the gap's width there
  double needed = 0.0;       // Å
  double crease_degrees = 0.0;  // "crease" only
};

struct MembraneFit {
  std::optional<RemeshReport> remesh;
  std::vector<TightFeature> tight;  // tightest (smallest found / needed) first; empty when it fits
  double scale_needed = 1.0;        // the mesh would fit scaled by this (> 1 when it does not fit now)
  double thinnest_wall = 0.0, narrowest_gap = 0.0;  // Å, over the whole prepared mesh (INFINITY: none)
  bool fits() const { return tight.empty(); }
};

// Judges `mesh` (scaled to its final size; its check-mesh `report`) for a bilayer `thickness` Å thick
// on the user's own triangles — a wall thinner than the bilayer, a gap narrower than it, a crease
// whose rounding would leave less — and, when it fits, remeshes it if the policy and its creases or
// slivers ask, replacing `report`. Throws std::invalid_argument when the mesh has problems besides UVs and slivers and
// would need remeshing (remeshing does not guess at a shape), naming the first.
MembraneFit fit_membrane(ProxyMesh& mesh, MeshReport& report, double thickness, const RemeshPolicy& policy);

// "FILE: ..." lines naming the tightest features (at most `shown`) and the smallest diameter (when the
// mesh was sized by `diameter`, Å) or scale at which the mesh would take the bilayer.
std::string describe_tight_features(const MembraneFit& fit, double thickness, std::optional<double> diameter,
                                    std::size_t shown = 5);

}  // namespace nano::mesh
