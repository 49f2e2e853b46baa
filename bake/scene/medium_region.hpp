#pragma once
// Where a scene's medium lies (scene.json "medium", docs/scene.md): the region it fills, and the
// checks of that region against what it holds and what it surrounds, made once the meshes are
// measured and the instances placed by trial, so a medium that cannot work is refused in seconds,
// before any tile is packed.
#include <span>

#include <glm/vec3.hpp>

#include "bake/scene/scene_description.hpp"
#include "bake/scene/scene_feasibility.hpp"

namespace nano::scene {

// A placed compartment instance as the medium sees it: the world sphere that holds its mesh.
struct InstanceSphere {
  glm::dvec3 centre{0.0};
  double radius = 0.0;
};

// The spheres of placed instances: `bounding_radius[c]` encloses compartment c about its origin in
// compartment space; an instance that scales grows it by its largest stretch.
std::vector<InstanceSphere> instance_spheres(std::span<const PlacedInstance> placed,
                                             std::span<const double> bounding_radius);

// The medium's margin beyond the instances when the scene gives neither region nor margin.
double default_medium_margin(const SolubleDescription& medium);

// The box the medium fills: the scene's region, or the instances' spheres' bounds grown by the
// margin. Requires scene.medium.
Box medium_region(const SceneDescription& scene, std::span<const InstanceSphere> instances);

// Refuses (InputError naming "medium.region" or "medium.margin" and the value that works) a
// region narrower on some axis than the diameter of the largest molecule the medium holds, and a
// region that no instance's sphere reaches (a medium around nothing is a soluble: give it a
// compartment). Does nothing without a medium.
void check_medium_region(const SceneDescription& scene, std::span<const MoleculeMeasure> molecules,
                         std::span<const InstanceSphere> instances);

}  // namespace nano::scene
