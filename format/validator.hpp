#pragma once
// Semantic validation of an opened package: every index in range, every float finite, every AABB
// ordered, every referenced section present, every value in its documented domain. Together with
// the structural checks of Package::open this is what `nanoview validate` runs; a package that
// passes can be uploaded without further checks.
#include <filesystem>

#include "format/package.hpp"

namespace nano::format {

// Throws PackageError on the first broken rule, naming the section and byte offset.
void validate_semantics(const Package& package);

// Package::open followed by validate_semantics.
Package open_validated(const std::filesystem::path& path);

}  // namespace nano::format
