#pragma once
// Strict JSON reading for hand-written input files (scene.json, camera paths): a syntax error names
// its line and column, and a repeated key in one object is an error (plain JSON parsers silently
// keep one of them).
// Hostile input (a huge file, endless nesting, a giant string, a number beyond a double) is
// refused with an InputError in time and memory proportional to the bounds below.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace nano {

// Object members keep the file's order, so everything derived from them is deterministic.
using Json = nlohmann::ordered_json;

// Bounds far above any real scene: a scene with 10^5 explicit instance transforms is about 20 MB,
// the deepest nesting of the schema is under 10 levels, names and paths are short.
inline constexpr std::uintmax_t kMaxJsonFileBytes = std::uintmax_t(64) << 20;  // 64 MiB
inline constexpr std::size_t kMaxJsonDepth = 64;                                // nested arrays and objects
inline constexpr std::size_t kMaxJsonStringBytes = std::size_t(1) << 20;        // 1 MiB, keys included
// Numbers, strings, booleans, nulls, arrays and objects (keys not counted). A parsed value takes
// 16 to 70 bytes, so this keeps a document under about 300 MB; 10^5 explicit instances with a
// "matrix" each are 1.8·10^6 values.
inline constexpr std::size_t kMaxJsonValues = std::size_t(1) << 22;             // 4194304

// Parses `text`; errors name `file_for_messages` and either "LINE:COLUMN" (syntax, nesting) or
// the key path (a duplicated key, a string longer than kMaxJsonStringBytes, a number that
// overflows a double, such as 1e400, the value past kMaxJsonValues). Throws nano::InputError.
Json parse_json_text(std::string_view text, const std::string& file_for_messages);

// Reads the whole file and parses it; a missing or unreadable file, or one larger than
// kMaxJsonFileBytes (refused before it is read), is an InputError too.
Json read_json_file(const std::filesystem::path& path);

}  // namespace nano
