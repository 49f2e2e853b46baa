#include "runtime/vk/pipeline_cache.hpp"

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#define XXH_STATIC_LINKING_ONLY  // XXH3_state_t on the stack
#include <xxhash.h>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "runtime/vk/error.hpp"

namespace nano::vk {
namespace {

constexpr char kMagic[4] = {'N', 'U', 'P', 'C'};

// Byte offsets of the file header (pipeline_cache.hpp draws it).
namespace offset {
constexpr std::size_t magic = 0, version = 4, key = 8, payload_size = 76, checksum = 84;
}
constexpr std::size_t kKeyBytes = offset::payload_size - offset::key;
static_assert(kKeyBytes == 3 * 4 + 3 * VK_UUID_SIZE + 8 && offset::checksum + 8 == kPipelineCacheHeaderBytes);

// VkPipelineCacheHeaderVersionOne: headerSize, headerVersion, vendorID, deviceID, pipelineCacheUUID.
constexpr std::size_t kVulkanHeaderBytes = 16 + VK_UUID_SIZE;

// Little-endian fields, written byte by byte so the file does not depend on the host's layout.
template <class T> void put(std::span<std::byte> out, std::size_t at, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out[at + i] = static_cast<std::byte>((std::uint64_t(value) >> (8 * i)) & 0xff);
}
template <class T> T get(std::span<const std::byte> in, std::size_t at) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) value |= std::uint64_t(std::to_integer<std::uint8_t>(in[at + i])) << (8 * i);
  return static_cast<T>(value);
}
void put_uuid(std::span<std::byte> out, std::size_t at, const std::array<std::uint8_t, VK_UUID_SIZE>& uuid) {
  for (std::size_t i = 0; i < VK_UUID_SIZE; ++i) out[at + i] = std::byte{uuid[i]};
}
std::array<std::uint8_t, VK_UUID_SIZE> get_uuid(std::span<const std::byte> in, std::size_t at) {
  std::array<std::uint8_t, VK_UUID_SIZE> uuid{};
  for (std::size_t i = 0; i < VK_UUID_SIZE; ++i) uuid[i] = std::to_integer<std::uint8_t>(in[at + i]);
  return uuid;
}
std::array<std::uint8_t, VK_UUID_SIZE> to_uuid(const std::uint8_t (&bytes)[VK_UUID_SIZE]) {
  std::array<std::uint8_t, VK_UUID_SIZE> uuid{};
  std::copy(std::begin(bytes), std::end(bytes), uuid.begin());
  return uuid;
}

// The key as it stands in the header; also what the file name hashes.
std::array<std::byte, kKeyBytes> encode_key(const PipelineCacheKey& key) {
  std::array<std::byte, kKeyBytes> bytes{};
  put(bytes, 0, key.vendor_id);
  put(bytes, 4, key.device_id);
  put(bytes, 8, key.driver_version);
  put_uuid(bytes, 12, key.pipeline_cache_uuid);
  put_uuid(bytes, 28, key.device_uuid);
  put_uuid(bytes, 44, key.driver_uuid);
  put(bytes, 60, key.shader_hash);
  return bytes;
}

PipelineCacheKey decode_key(std::span<const std::byte> bytes) {
  PipelineCacheKey key;
  key.vendor_id = get<std::uint32_t>(bytes, 0);
  key.device_id = get<std::uint32_t>(bytes, 4);
  key.driver_version = get<std::uint32_t>(bytes, 8);
  key.pipeline_cache_uuid = get_uuid(bytes, 12);
  key.device_uuid = get_uuid(bytes, 28);
  key.driver_uuid = get_uuid(bytes, 44);
  key.shader_hash = get<std::uint64_t>(bytes, 60);
  return key;
}

// Header up to the checksum, then the payload: a flipped bit in the key reads as damage, not as a
// file of another device.
std::uint64_t file_checksum(std::span<const std::byte> header, std::span<const std::byte> payload) {
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  XXH3_64bits_update(&state, header.data(), offset::checksum);
  XXH3_64bits_update(&state, payload.data(), payload.size());
  return XXH3_64bits_digest(&state);
}

std::string hex(std::uint64_t value, int digits) {
  char text[17];
  std::snprintf(text, sizeof text, "%0*" PRIx64, digits, value);
  return text;
}

std::string compared(const char* what, std::uint32_t file, std::uint32_t device) {
  return std::string(what) + " 0x" + hex(file, 4) + ", this device has 0x" + hex(device, 4);
}

// Why the file's key is not the device's, or "" when it is: the first field that differs.
std::string key_mismatch(const PipelineCacheKey& file, const PipelineCacheKey& device) {
  const std::string other = "written for another ";
  if (file.vendor_id != device.vendor_id) return other + compared("vendor:", file.vendor_id, device.vendor_id);
  if (file.device_id != device.device_id) return other + compared("device:", file.device_id, device.device_id);
  if (file.driver_version != device.driver_version)
    return other + compared("driver version:", file.driver_version, device.driver_version);
  if (file.pipeline_cache_uuid != device.pipeline_cache_uuid) return other + "pipeline cache UUID";
  if (file.device_uuid != device.device_uuid) return other + "device UUID";
  if (file.driver_uuid != device.driver_uuid) return other + "driver UUID";
  if (file.shader_hash != device.shader_hash) return other + "build of the shaders";
  return {};
}

// The payload's own VkPipelineCacheHeaderVersionOne must name this device too: our key says what
// we meant to store, this says what the driver actually handed us.
std::string vulkan_header_mismatch(std::span<const std::byte> payload, const PipelineCacheKey& device) {
  if (payload.size() < kVulkanHeaderBytes)
    return "driver data of " + std::to_string(payload.size()) + " bytes is shorter than a Vulkan cache header";
  const auto header_size = get<std::uint32_t>(payload, 0);
  const auto header_version = get<std::uint32_t>(payload, 4);
  if (header_size < kVulkanHeaderBytes || header_size > payload.size())
    return "Vulkan cache header size " + std::to_string(header_size) + " does not fit its " +
           std::to_string(payload.size()) + " bytes";
  if (header_version != VK_PIPELINE_CACHE_HEADER_VERSION_ONE)
    return "Vulkan cache header version " + std::to_string(header_version) + ", expected 1";
  const std::string other = "driver data for another ";
  if (get<std::uint32_t>(payload, 8) != device.vendor_id)
    return other + compared("vendor:", get<std::uint32_t>(payload, 8), device.vendor_id);
  if (get<std::uint32_t>(payload, 12) != device.device_id)
    return other + compared("device:", get<std::uint32_t>(payload, 12), device.device_id);
  if (get_uuid(payload, 16) != device.pipeline_cache_uuid) return other + "pipeline cache UUID";
  return {};
}

// The whole file; nullopt when there is none (the first run, which is no reason to warn; nor is a
// file where a folder should be, which the first save reports).
std::optional<std::vector<std::byte>> read_if_present(const std::filesystem::path& file) {
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (f == nullptr) {
    if (errno == ENOENT || errno == ENOTDIR) return std::nullopt;
    throw PipelineCacheFileError(std::string("cannot open it: ") + std::strerror(errno));
  }
  std::vector<std::byte> bytes;
  std::byte chunk[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
  const bool failed = std::ferror(f) != 0;
  const int error = errno;
  std::fclose(f);
  if (failed) throw PipelineCacheFileError(std::string("cannot read it: ") + std::strerror(error));
  return bytes;
}

// The payload `file` holds for `key`; nullopt when there is no file. Throws PipelineCacheFileError.
std::optional<std::vector<std::byte>> load_payload(const std::filesystem::path& file, const PipelineCacheKey& key) {
  const auto bytes = read_if_present(file);
  if (!bytes) return std::nullopt;
  const PipelineCacheFileContents contents = decode_pipeline_cache_file(*bytes);
  if (const std::string wrong = key_mismatch(contents.key, key); !wrong.empty()) throw PipelineCacheFileError(wrong);
  if (const std::string wrong = vulkan_header_mismatch(contents.payload, key); !wrong.empty())
    throw PipelineCacheFileError(wrong);
  return std::vector<std::byte>(contents.payload.begin(), contents.payload.end());
}

// The warnings are single lines on stderr: a cache is an optimisation, so nothing about it may stop
// a run, but a cache that never works should not go unnoticed either.
void warn_unusable_file(const std::filesystem::path& file, const std::string& what) {
  std::fprintf(stderr, "nanoview: warning: pipeline cache %s: %s; starting with an empty cache\n", file.c_str(), what.c_str());
}
void warn_no_directory() {
  std::fprintf(stderr,
               "nanoview: warning: pipeline cache: neither XDG_CACHE_HOME nor HOME is an absolute path; compiled "
               "pipelines are not kept across runs\n");
}
void warn_not_saved(const std::filesystem::path& file, const std::string& what) {
  std::fprintf(stderr, "nanoview: warning: pipeline cache %s: cannot save it (%s); compiled pipelines are not kept for the next run\n",
               file.c_str(), what.c_str());
}

// The warning names the file already; write_file_atomically's InputError names it again.
std::string complaint(const std::exception& e) {
  const auto* input_error = dynamic_cast<const InputError*>(&e);
  return input_error ? input_error->rule() : e.what();
}

}  // namespace

PipelineCacheKey pipeline_cache_key(VkPhysicalDevice physical_device, std::uint64_t shader_hash) {
  VkPhysicalDeviceIDProperties ids{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &ids;
  vkGetPhysicalDeviceProperties2(physical_device, &properties);
  PipelineCacheKey key;
  key.vendor_id = properties.properties.vendorID;
  key.device_id = properties.properties.deviceID;
  key.driver_version = properties.properties.driverVersion;
  key.pipeline_cache_uuid = to_uuid(properties.properties.pipelineCacheUUID);
  key.device_uuid = to_uuid(ids.deviceUUID);
  key.driver_uuid = to_uuid(ids.driverUUID);
  key.shader_hash = shader_hash;
  return key;
}

std::optional<std::filesystem::path> pipeline_cache_file(const PipelineCacheKey& key) {
  const auto directory = user_cache_directory();
  if (!directory) return std::nullopt;
  const auto key_bytes = encode_key(key);
  return *directory / "nanouniverse" / ("pipelines-" + hex(XXH3_64bits(key_bytes.data(), key_bytes.size()), 16) + ".bin");
}

std::vector<std::byte> encode_pipeline_cache_file(const PipelineCacheKey& key, std::span<const std::byte> payload) {
  std::vector<std::byte> bytes(kPipelineCacheHeaderBytes + payload.size());
  const std::span<std::byte> out(bytes);
  for (std::size_t i = 0; i < sizeof kMagic; ++i) out[offset::magic + i] = std::byte(kMagic[i]);
  put(out, offset::version, kPipelineCacheFormatVersion);
  const auto key_bytes = encode_key(key);
  std::copy(key_bytes.begin(), key_bytes.end(), out.begin() + offset::key);
  put(out, offset::payload_size, std::uint64_t(payload.size()));
  std::copy(payload.begin(), payload.end(), out.begin() + kPipelineCacheHeaderBytes);
  put(out, offset::checksum, file_checksum(out, payload));
  return bytes;
}

PipelineCacheFileContents decode_pipeline_cache_file(std::span<const std::byte> bytes) {
  if (bytes.size() < kPipelineCacheHeaderBytes)
    throw PipelineCacheFileError("truncated: " + std::to_string(bytes.size()) + " bytes, shorter than the " +
                                 std::to_string(kPipelineCacheHeaderBytes) + "-byte header");
  if (std::memcmp(bytes.data() + offset::magic, kMagic, sizeof kMagic) != 0)
    throw PipelineCacheFileError("not a nanouniverse pipeline cache (no NUPC magic)");
  if (const auto version = get<std::uint32_t>(bytes, offset::version); version != kPipelineCacheFormatVersion)
    throw PipelineCacheFileError("format version " + std::to_string(version) + ", this build reads " +
                                 std::to_string(kPipelineCacheFormatVersion));
  const auto payload_size = get<std::uint64_t>(bytes, offset::payload_size);
  const std::size_t stored = bytes.size() - kPipelineCacheHeaderBytes;
  if (payload_size != stored)
    throw PipelineCacheFileError((payload_size > stored ? "truncated: " : "damaged: ") + std::to_string(stored) +
                                 " payload bytes where the header announces " + std::to_string(payload_size));
  const auto payload = bytes.subspan(kPipelineCacheHeaderBytes);
  if (get<std::uint64_t>(bytes, offset::checksum) != file_checksum(bytes, payload))
    throw PipelineCacheFileError("damaged: checksum mismatch");
  return {decode_key(bytes.subspan(offset::key, kKeyBytes)), payload};
}

PipelineCache::PipelineCache(VkDevice device, const PipelineCacheKey& key, std::optional<std::filesystem::path> file)
    : device_(device), key_(key), file_(std::move(file)) {
  std::optional<std::vector<std::byte>> loaded;
  if (!file_) {
    warn_no_directory();
  } else {
    try {
      loaded = load_payload(*file_, key_);
    } catch (const PipelineCacheFileError& e) {
      warn_unusable_file(*file_, e.what());
    }
  }
  // The file is rewritten only when the driver has more to say than it holds. Without a usable
  // file (none yet, or one rejected here or by the driver) the first save writes: a bad file then
  // warns once, not at every start.
  if (loaded) {
    const VkResult result = create(*loaded);
    if (result == VK_SUCCESS) {
      saved_ = fingerprint(data());
      return;
    }
    // Every check passed and the driver still refused: its data, its call; start afresh.
    warn_unusable_file(*file_, std::string("the driver rejected its data (") + result_name(result) + ")");
  }
  check(create({}), "vkCreatePipelineCache");
}

VkResult PipelineCache::create(std::span<const std::byte> initial_data) {
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = initial_data.size();
  info.pInitialData = initial_data.empty() ? nullptr : initial_data.data();
  return vkCreatePipelineCache(device_, &info, nullptr, &cache_);
}

PipelineCache::~PipelineCache() {
  save();
  vkDestroyPipelineCache(device_, cache_, nullptr);
}

std::vector<std::byte> PipelineCache::data() const {
  // Another thread may add pipelines between asking for the size and the bytes (VK_INCOMPLETE): ask again.
  for (;;) {
    std::size_t size = 0;
    check(vkGetPipelineCacheData(device_, cache_, &size, nullptr), "vkGetPipelineCacheData");
    std::vector<std::byte> bytes(size);
    const VkResult result = vkGetPipelineCacheData(device_, cache_, &size, bytes.data());
    if (result == VK_INCOMPLETE) continue;
    check(result, "vkGetPipelineCacheData");
    bytes.resize(size);
    return bytes;
  }
}

bool PipelineCache::save() {
  if (!file_) return false;
  const std::lock_guard lock(save_mutex_);
  if (save_failed_) return false;
  try {
    const std::vector<std::byte> payload = data();
    const Fingerprint now = fingerprint(payload);
    if (now == saved_) return false;
    std::filesystem::create_directories(file_->parent_path());
    write_file_atomically(*file_, encode_pipeline_cache_file(key_, payload));
    saved_ = now;
    return true;
  } catch (const std::exception& e) {  // writing, creating the folder, Vulkan or memory
    save_failed_ = true;
    warn_not_saved(*file_, complaint(e));
    return false;
  }
}

PipelineCache::Fingerprint PipelineCache::fingerprint(std::span<const std::byte> data) {
  return {data.size(), XXH3_64bits(data.data(), data.size())};
}

}  // namespace nano::vk
