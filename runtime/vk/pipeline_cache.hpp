#pragma once
// A VkPipelineCache kept across runs in the user's cache directory, so that a second start does not
// pay again for the shader compilation the first one did (render.comp takes seconds on lavapipe).
//
// The file is ours, not the driver's raw bytes: the Vulkan spec only allows handing
// vkCreatePipelineCache data that the same driver returned from vkGetPipelineCacheData, and a
// driver is free to crash on anything else. So the file carries the key it was written for and a
// checksum, and every check runs before the driver sees a byte; a file that fails one is ignored
// with one warning line on stderr and the run starts with an empty cache. Layout (little-endian):
//
//   offset  size  field
//        0     4  magic "NUPC"
//        4     4  format version (kPipelineCacheFormatVersion)
//        8    68  the PipelineCacheKey the file was written for:
//                   8 vendorID, 12 deviceID, 16 driverVersion (4 bytes each),
//                   20 pipelineCacheUUID, 36 deviceUUID, 52 driverUUID (16 bytes each),
//                   68 shader hash (8 bytes)
//       76     8  payload size in bytes
//       84     8  checksum: XXH3-64 of bytes [0, 84) followed by the payload
//       92     …  payload: the bytes of vkGetPipelineCacheData
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "common/user_cache_directory.hpp"

namespace nano::vk {

inline constexpr std::uint32_t kPipelineCacheFormatVersion = 1;
inline constexpr std::size_t kPipelineCacheHeaderBytes = 92;

// What a cache file must have been written for. The device and driver fields decide whether the
// driver can use the data at all; the shader hash keeps entries of shaders this build no longer
// has out of the file (they would only make it grow).
struct PipelineCacheKey {
  std::uint32_t vendor_id = 0, device_id = 0, driver_version = 0;
  std::array<std::uint8_t, VK_UUID_SIZE> pipeline_cache_uuid{}, device_uuid{}, driver_uuid{};
  std::uint64_t shader_hash = 0;
  bool operator==(const PipelineCacheKey&) const = default;
};

// The key of `physical_device` (Vulkan 1.1 device ID properties) for shaders hashing to `shader_hash`.
PipelineCacheKey pipeline_cache_key(VkPhysicalDevice physical_device, std::uint64_t shader_hash);

// The user's cache directory: common/user_cache_directory.hpp.
using nano::user_cache_directory;

// <user_cache_directory()>/nanouniverse/pipelines-<16 hex digits of a hash of the key>.bin, or
// nullopt without a usable cache directory.
std::optional<std::filesystem::path> pipeline_cache_file(const PipelineCacheKey& key);

// What is wrong with the bytes of a cache file; PipelineCache turns it into its warning line.
class PipelineCacheFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The bytes of a cache file holding `payload` (vkGetPipelineCacheData) written for `key`.
std::vector<std::byte> encode_pipeline_cache_file(const PipelineCacheKey& key, std::span<const std::byte> payload);

struct PipelineCacheFileContents {
  PipelineCacheKey key;
  std::span<const std::byte> payload;  // points into the bytes given to decode_pipeline_cache_file
};

// The key and payload of a cache file's bytes. Checks the structure (size, magic, version, payload
// size, checksum), not whether the key is the device's; throws PipelineCacheFileError otherwise.
PipelineCacheFileContents decode_pipeline_cache_file(std::span<const std::byte> bytes);

// A VkPipelineCache loaded from and saved to one file. Pipelines may be created with handle() from
// several threads at once (the cache is not created externally synchronized) while save() runs.
class PipelineCache {
public:
  // Loads `file` when it exists and holds data for `key` (vendorID, deviceID and pipelineCacheUUID
  // of the payload's own Vulkan header included); anything wrong with it is one warning line on
  // stderr and an empty cache, never an exception. Without a file (no usable cache directory) the
  // cache lives in memory only, again with one warning line. Throws only when Vulkan cannot
  // create even an empty cache.
  PipelineCache(VkDevice device, const PipelineCacheKey& key, std::optional<std::filesystem::path> file);
  ~PipelineCache();  // saves, then destroys the cache
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  const std::optional<std::filesystem::path>& file() const { return file_; }

  // What vkGetPipelineCacheData returns now: what save() writes as the payload.
  std::vector<std::byte> data() const;

  // Writes the file (atomically, creating its folder) unless it already holds data(): when the
  // data changed since it was loaded or last saved, or no sound file was loaded (none yet, or one
  // that was rejected). Returns whether it wrote. Thread-safe. Never throws: a failure is one
  // warning line, after which this cache stops trying (the next run compiles again, nothing worse).
  bool save();

private:
  struct Fingerprint {
    std::size_t size = 0;
    std::uint64_t hash = 0;
    bool operator==(const Fingerprint&) const = default;
  };
  static Fingerprint fingerprint(std::span<const std::byte> data);
  VkResult create(std::span<const std::byte> initial_data);  // into cache_

  VkDevice device_ = VK_NULL_HANDLE;
  PipelineCacheKey key_;
  std::optional<std::filesystem::path> file_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::mutex save_mutex_;                // guards the two fields below and the file
  std::optional<Fingerprint> saved_;     // of the data the file holds; nullopt: none, or not ours
  bool save_failed_ = false;
};

}  // namespace nano::vk
