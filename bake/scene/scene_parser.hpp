#pragma once
// scene.json -> SceneDescription, with every rule of docs/scene.md checked. Any violation throws
// nano::InputError whose message reads "scene.json:KEY.PATH: RULE".
#include <filesystem>

#include "common/json_document.hpp"
#include "bake/scene/scene_description.hpp"

namespace nano::scene {

// `scene_file` names the document in messages, and relative paths inside it are resolved
// against its folder (they are not opened here: the readers check existence).
SceneDescription parse_scene_description(const Json& document, const std::filesystem::path& scene_file);

// read_json_file + parse_scene_description.
SceneDescription load_scene_description(const std::filesystem::path& scene_file);

}  // namespace nano::scene
