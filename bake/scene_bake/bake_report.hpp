#pragma once
// The bake report (--report): what the package represents and what it cost.
#include <nlohmann/json.hpp>

#include "bake/scene_bake/scene_baker.hpp"
#include "format/package.hpp"

namespace nano::scene_bake {

// Keys: represented_atoms, compartments [{name, mesh, triangles, represented_atoms, copies {type: n},
// core_boxes {inside, boundary}, replication_area [W, H]}], instances [{compartment, aabb}],
// densities [{set, molecule, requested, achieved}], membrane_surfaces {membrane: {chart_stretch,
// curvature (rad/Å), normal_tilt (tan)} its tiles were packed to survive}, level_of_detail {name: {types,
// atoms, beads}} (conformers of one species summed), sections {kind: stored bytes}, package_bytes,
// stages {stage: seconds}.
nlohmann::ordered_json bake_report(const BakedScene& scene, const format::Package& package);

// A short human summary of the same.
std::string bake_summary(const BakedScene& scene, const format::Package& package);

}  // namespace nano::scene_bake
