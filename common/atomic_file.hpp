#pragma once
// Output files appear whole or not at all: bytes go to a temporary name beside the target and
// are renamed over it only after a successful flush, so a crash or an error never leaves a
// partial package, mesh or export behind.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>

namespace nano {

// Writes `bytes` to `path` atomically. Throws InputError naming the path on any I/O failure.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

// Streams into a temporary file through `fill` and renames it to `path` if `fill` returns
// normally; on an exception the temporary file is removed and the exception propagates.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::FILE*)>& fill);

// Makes SIGINT and SIGTERM remove the temporary file a write_file_atomically is filling before the
// signal ends the process as it would have, so an interrupted command leaves no file behind.
void remove_temporaries_on_interrupt();

}  // namespace nano
