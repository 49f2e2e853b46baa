#pragma once
// Seeded random placement of compartment instances: bounding spheres that do not overlap, with
// uniformly random orientations, inside a box. Same seed, same transforms, on every platform.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bake/scene/scene_description.hpp"

namespace nano::scene {

// Rejection attempts per copy before a placement is declared impossible.
inline constexpr int placement_attempts_per_copy = 2000;

// The seed of random-placement entry `entry_index` when the file gives none.
std::uint64_t derive_placement_seed(std::uint64_t scene_seed, std::size_t entry_index);

// How many instances the scene has once every random placement is expanded.
std::size_t expanded_instance_count(const SceneDescription& scene);

// Expands every RandomPlacement into explicit instances, keeping the entry order. Each copy gets
// a centre uniform in the box shrunk by its radius and a uniformly random rotation; a candidate
// is rejected while its sphere comes closer than the entry's min_gap to any sphere placed before
// it (explicit instances included, their radius grown by the transform's largest stretch).
// `bounding_radius[i]`: radius about the origin of compartment i in compartment space (scale
// applied), enclosing the mesh and its shell. Throws nano::InputError naming the entry when the
// spheres do not fit.
std::vector<PlacedInstance> expand_random_instances(const SceneDescription& scene,
                                                    const std::vector<double>& bounding_radius);

}  // namespace nano::scene
