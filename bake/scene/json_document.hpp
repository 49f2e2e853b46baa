#pragma once
// Strict JSON reading for hand-written input files: a syntax error names its line and column,
// and a repeated key in one object is an error (plain JSON parsers silently keep one of them).
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace nano::scene {

// Object members keep the file's order, so everything derived from them is deterministic.
using Json = nlohmann::ordered_json;

// Parses `text`; errors name `file_for_messages` and either "LINE:COLUMN" or the key path of a
// duplicated key. Throws nano::InputError.
Json parse_json_text(std::string_view text, const std::string& file_for_messages);

// Reads the whole file and parses it; a missing or unreadable file is an InputError too.
Json read_json_file(const std::filesystem::path& path);

}  // namespace nano::scene
