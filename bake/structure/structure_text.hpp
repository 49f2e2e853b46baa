#pragma once
// Loads a structure file into memory whole (one read, no per-line streams), inflating gzip
// transparently, and rejects binary files before any parser sees them.
#include <filesystem>
#include <string>

namespace nano::structure {

// Returns the file's text. A gzip stream is recognised by its magic bytes, not by the name.
// Throws InputError for a missing/unreadable file, corrupt or truncated gzip, or binary content.
std::string read_structure_text(const std::filesystem::path& path);

// The same from the file's bytes in memory (what read_structure_text does once it has read them):
// inflated when they start with the gzip magic, then checked to be text. `name` only labels errors.
std::string structure_text_from_bytes(std::string bytes, const std::string& name);

}  // namespace nano::structure
