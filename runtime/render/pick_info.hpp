#pragma once
// What a picked pixel shows: the ids of a gpu::PixelHit (GPU frame or CPU oracle) resolved against
// the package into names a person can read — atom, residue, chain, molecule type and its source
// file, compartment, and where virtual instancing placed the copy. Used by `nanoview pick` and the
// viewer's info panel.
#include <string>

#include <nlohmann/json.hpp>

#include "format/package.hpp"
#include "shared/camera.h"

namespace nano::render {

// {"hit": false} for the background; otherwise {"hit": true, "depth" (Å along the unit ray),
// "atom": {index, index_in_molecule, name, element, chain, residue_name, residue_number,
// insertion_code and alt_location (only when set), position (molecule space, Å), radius},
// "molecule": {type, name, source}, "compartment_instance": {index, compartment, name (if named)},
// "placement": {kind "membrane" | "core", triangle + tile [a, b] + wang_square | box + box_ijk
// [i, j, k] + wang_cube, copy (molecule index in its tile), copy_number}}. Every id of `hit` is
// checked against the package before it is used, and so are the package indices it leads to: ids
// that name nothing, or that contradict each other (an atom outside the molecule type of the copy
// the ids name, a box index that is not its (i, j, k)), give {"hit": true, "error": "..."}.
nlohmann::json describe_hit(const format::Package& package, const gpu::PixelHit& hit);

// A few lines for a GUI panel, from describe_hit's JSON (no trailing newline).
std::string describe_hit_text(const nlohmann::json& description);

}  // namespace nano::render
