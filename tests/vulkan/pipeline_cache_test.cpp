// Issue #26 item 5: the persistent pipeline cache (runtime/vk/pipeline_cache.hpp). Every test
// points XDG_CACHE_HOME and HOME at a fresh temporary folder, builds the small smoke-test pipeline
// (render.comp takes too long on lavapipe) and runs with the validation layer on, so a bad file
// that reached the driver would show up as a validation error, not only as a crash.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "runtime/vk/compute_pipeline.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/embedded_shaders.hpp"
#include "runtime/vk/instance.hpp"
#include "runtime/vk/pipeline_cache.hpp"
#include "shared/smoke_ray_query.h"

extern const uint32_t nano_spv_smoke_ray_query_comp[];
extern const std::size_t nano_spv_smoke_ray_query_comp_words;

namespace {

namespace fs = std::filesystem;
using namespace nano::vk;

constexpr std::uint64_t kShaderHash = 0x5eed'cafe'f00d'0001;
constexpr std::size_t kVulkanHeaderBytes = 32;  // VkPipelineCacheHeaderVersionOne

std::vector<std::byte> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto* first = reinterpret_cast<const std::byte*>(text.data());
  return {first, first + text.size()};
}

void write_bytes(const fs::path& path, std::span<const std::byte> bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

ino_t inode(const fs::path& path) {
  struct stat s {};
  EXPECT_EQ(stat(path.c_str(), &s), 0) << path;
  return s.st_ino;
}

// Lines of `text` that are our warnings; lavapipe's own conformance notice is not one of them.
std::vector<std::string> warning_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.starts_with("nanoview: warning:")) lines.push_back(line);
  return lines;
}

// Sets an environment variable for one test and puts the old value back afterwards.
class ScopedEnvironment {
public:
  ScopedEnvironment(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    set(value);
  }
  ~ScopedEnvironment() { set(old_); }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

private:
  void set(const std::optional<std::string>& value) {
    if (value) setenv(name_, value->c_str(), 1);
    else unsetenv(name_);
  }
  const char* name_;
  std::optional<std::string> old_;
};

ComputePipelineDesc smoke_pipeline_desc(std::uint32_t workgroup_size = 64) {
  ComputePipelineDesc desc;
  desc.code = {nano_spv_smoke_ray_query_comp, nano_spv_smoke_ray_query_comp_words};
  desc.sets = {{{0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
                {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}}};
  desc.push_constant_bytes = sizeof(std::uint32_t);
  desc.specialization.set(nano::gpu::kSmokeWorkgroupSizeConstantId, workgroup_size);
  return desc;
}

std::vector<std::byte> cache_data(const Device& device) {
  std::size_t size = 0;
  EXPECT_EQ(vkGetPipelineCacheData(device.handle(), device.pipeline_cache(), &size, nullptr), VK_SUCCESS);
  std::vector<std::byte> bytes(size);
  EXPECT_EQ(vkGetPipelineCacheData(device.handle(), device.pipeline_cache(), &size, bytes.data()), VK_SUCCESS);
  bytes.resize(size);
  return bytes;
}

class PipelineCacheTest : public testing::Test {
protected:
  static void SetUpTestSuite() {
    // Mesa's own disk cache also lives under XDG_CACHE_HOME; kept out of the test's folders (and
    // out of the working directory when the test sets a relative XDG_CACHE_HOME).
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
    instance_ = new Instance(InstanceOptions{.validation = true});
  }
  static void TearDownTestSuite() {
    delete instance_;
    instance_ = nullptr;
  }

  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "nano-pipeline-cache-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
    xdg_.emplace("XDG_CACHE_HOME", (root_ / "xdg").string());
    home_.emplace("HOME", (root_ / "home").string());
  }
  void TearDown() override {
    xdg_.reset();
    home_.reset();
    fs::remove_all(root_);
    EXPECT_EQ(instance_->validation_errors(), 0u);
  }

  static Device open_device(bool persistent = true, std::uint64_t shader_hash = kShaderHash) {
    return open_ray_query_device(*instance_,
                                 DeviceOptions{.persistent_pipeline_cache = persistent, .shader_hash = shader_hash});
  }
  // open_device with stderr captured into `err`.
  static Device open_device_capturing(std::string& err) {
    testing::internal::CaptureStderr();
    try {
      Device device = open_device();
      err = testing::internal::GetCapturedStderr();
      return device;
    } catch (...) {
      err = testing::internal::GetCapturedStderr();
      throw;
    }
  }
  static fs::path cache_file_of(const Device& device, std::uint64_t shader_hash = kShaderHash) {
    return pipeline_cache_file(pipeline_cache_key(device.physical_device(), shader_hash)).value();
  }
  // A cache file as a first run leaves it: the smoke pipeline compiled and saved.
  static std::vector<std::byte> valid_file_bytes(fs::path* where = nullptr) {
    const Device device = open_device();
    const ComputePipeline pipeline(device, smoke_pipeline_desc());
    if (where) *where = cache_file_of(device);
    return read_bytes(cache_file_of(device));
  }

  static Instance* instance_;
  fs::path root_;
  std::optional<ScopedEnvironment> xdg_, home_;
};

Instance* PipelineCacheTest::instance_ = nullptr;

// --- the file format, without a device ---

PipelineCacheKey sample_key() {
  PipelineCacheKey key;
  key.vendor_id = 0x10005;
  key.device_id = 0x1234;
  key.driver_version = 0x01020304;
  for (std::uint8_t i = 0; i < VK_UUID_SIZE; ++i) {
    key.pipeline_cache_uuid[i] = i;
    key.device_uuid[i] = std::uint8_t(0x40 + i);
    key.driver_uuid[i] = std::uint8_t(0x80 + i);
  }
  key.shader_hash = kShaderHash;
  return key;
}

TEST(PipelineCacheFile, RoundTripsKeyAndPayload) {
  const std::vector<std::byte> payload = {std::byte{1}, std::byte{2}, std::byte{3}};
  const std::vector<std::byte> bytes = encode_pipeline_cache_file(sample_key(), payload);
  ASSERT_EQ(bytes.size(), kPipelineCacheHeaderBytes + payload.size());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()), 4), "NUPC");
  EXPECT_EQ(std::to_integer<int>(bytes[4]), int(kPipelineCacheFormatVersion));  // little-endian
  EXPECT_EQ(std::to_integer<int>(bytes[16]), 0x04);                             // driverVersion at 16
  const PipelineCacheFileContents contents = decode_pipeline_cache_file(bytes);
  EXPECT_EQ(contents.key, sample_key());
  EXPECT_TRUE(std::ranges::equal(contents.payload, payload));
}

TEST(PipelineCacheFile, DecodeRejectsDamage) {
  const std::vector<std::byte> payload(40, std::byte{7});
  const std::vector<std::byte> good = encode_pipeline_cache_file(sample_key(), payload);
  const auto rejects = [](std::vector<std::byte> bytes, const std::string& expected) {
    try {
      decode_pipeline_cache_file(bytes);
      ADD_FAILURE() << "accepted; expected: " << expected;
    } catch (const PipelineCacheFileError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  rejects({}, "truncated: 0 bytes");
  rejects({good.begin(), good.begin() + 50}, "shorter than the 92-byte header");
  rejects({good.begin(), good.end() - 1}, "truncated: 39 payload bytes where the header announces 40");
  auto longer = good;
  longer.push_back(std::byte{0});
  rejects(longer, "damaged: 41 payload bytes");
  auto magic = good;
  magic[0] = std::byte{'X'};
  rejects(magic, "no NUPC magic");
  auto version = good;
  version[4] = std::byte{2};
  rejects(version, "format version 2");
  auto flipped_payload = good;
  flipped_payload.back() ^= std::byte{1};
  rejects(flipped_payload, "checksum mismatch");
  auto flipped_key = good;
  flipped_key[16] ^= std::byte{1};  // the checksum covers the key too
  rejects(flipped_key, "checksum mismatch");
}

TEST(PipelineCacheFile, UserCacheDirectoryFollowsXdg) {
  const ScopedEnvironment home("HOME", "/nonexistent-home");
  {
    const ScopedEnvironment xdg("XDG_CACHE_HOME", "/nonexistent-xdg");
    EXPECT_EQ(user_cache_directory(), fs::path("/nonexistent-xdg"));
  }
  using Value = std::optional<std::string>;
  for (const Value& ignored : {Value(), Value(""), Value("relative/cache")}) {
    const ScopedEnvironment xdg("XDG_CACHE_HOME", ignored);
    EXPECT_EQ(user_cache_directory(), fs::path("/nonexistent-home/.cache")) << ignored.value_or("(unset)");
  }
  const ScopedEnvironment xdg("XDG_CACHE_HOME", std::nullopt);
  for (const Value& unusable : {Value(), Value("home")}) {
    const ScopedEnvironment no_home("HOME", unusable);
    EXPECT_EQ(user_cache_directory(), std::nullopt);
    EXPECT_EQ(pipeline_cache_file(sample_key()), std::nullopt);
  }
}

TEST(PipelineCacheFile, FileNameHashesTheKey) {
  const ScopedEnvironment xdg("XDG_CACHE_HOME", "/nonexistent-xdg");
  const fs::path file = pipeline_cache_file(sample_key()).value();
  EXPECT_EQ(file.parent_path(), fs::path("/nonexistent-xdg/nanouniverse"));
  const std::string name = file.filename().string();
  ASSERT_EQ(name.size(), std::string("pipelines-0123456789abcdef.bin").size()) << name;
  EXPECT_TRUE(name.starts_with("pipelines-") && name.ends_with(".bin")) << name;
  EXPECT_EQ(name.find_first_not_of("0123456789abcdef", 10), name.size() - 4) << name;
  PipelineCacheKey other = sample_key();
  other.driver_version += 1;
  EXPECT_NE(pipeline_cache_file(other), file);
  other = sample_key();
  other.shader_hash += 1;
  EXPECT_NE(pipeline_cache_file(other), file);
  EXPECT_EQ(pipeline_cache_file(sample_key()), file);
}

TEST(EmbeddedShaders, HashCoversWordsAndModuleBoundaries) {
  const std::uint32_t a[] = {1, 2, 3}, b[] = {1, 2, 4}, ab[] = {1, 2, 3, 1, 2, 4};
  const SpirvCode one[] = {{a, 3}, {b, 3}};
  const SpirvCode same[] = {{a, 3}, {b, 3}};
  const SpirvCode swapped[] = {{b, 3}, {a, 3}};
  const SpirvCode joined[] = {{ab, 6}};
  const SpirvCode moved[] = {{ab, 4}, {ab + 4, 2}};
  EXPECT_EQ(hash_spirv(one), hash_spirv(same));
  EXPECT_NE(hash_spirv(one), hash_spirv(swapped));
  EXPECT_NE(hash_spirv(one), hash_spirv(joined));
  EXPECT_NE(hash_spirv(one), hash_spirv(moved));
  EXPECT_NE(hash_spirv(std::span(one, 1)), hash_spirv(std::span(swapped, 1)));  // a vs b: one word differs
  const SpirvCode smoke[] = {{nano_spv_smoke_ray_query_comp, nano_spv_smoke_ray_query_comp_words}};
  EXPECT_EQ(embedded_shader_hash(), embedded_shader_hash());
  EXPECT_NE(embedded_shader_hash(), hash_spirv(smoke));  // the other modules count too
  EXPECT_NE(embedded_shader_hash(), hash_spirv({}));
}

// --- on the device ---

TEST_F(PipelineCacheTest, KeyIsTheDevicesIdentity) {
  const Device device = open_device(false);
  const PipelineCacheKey key = pipeline_cache_key(device.physical_device(), kShaderHash);
  EXPECT_EQ(key.vendor_id, device.properties().vendorID);
  EXPECT_EQ(key.device_id, device.properties().deviceID);
  EXPECT_EQ(key.driver_version, device.properties().driverVersion);
  EXPECT_TRUE(std::ranges::equal(key.pipeline_cache_uuid, device.properties().pipelineCacheUUID));
  EXPECT_EQ(key.shader_hash, kShaderHash);
  EXPECT_NE(key.device_uuid, decltype(key.device_uuid){});  // lavapipe fills both UUIDs
  EXPECT_NE(key.driver_uuid, decltype(key.driver_uuid){});
}

TEST_F(PipelineCacheTest, FirstRunWritesTheFileAndTheSecondLoadsIt) {
  fs::path file;
  {
    std::string err;
    const Device device = open_device_capturing(err);
    EXPECT_TRUE(warning_lines(err).empty()) << err;
    ASSERT_NE(device.pipeline_cache(), VK_NULL_HANDLE);
    file = cache_file_of(device);
    EXPECT_EQ(file.parent_path(), root_ / "xdg" / "nanouniverse");
    EXPECT_FALSE(fs::exists(file)) << "nothing compiled yet";
    const ComputePipeline pipeline(device, smoke_pipeline_desc());
    ASSERT_TRUE(fs::exists(file)) << "saved right after the pipeline was built";
  }
  const std::vector<std::byte> written = read_bytes(file);
  const PipelineCacheFileContents contents = decode_pipeline_cache_file(written);
  // At least the driver's own header (lavapipe stores nothing else: its VkPipelineCache is a stub).
  EXPECT_GE(contents.payload.size(), kVulkanHeaderBytes);

  std::string err;
  const Device second = open_device_capturing(err);
  EXPECT_TRUE(warning_lines(err).empty()) << err;
  EXPECT_EQ(contents.key, pipeline_cache_key(second.physical_device(), kShaderHash));
  EXPECT_TRUE(std::ranges::equal(cache_data(second), contents.payload)) << "loaded what the first run saved";

  // The same pipeline again adds nothing, so the file is not rewritten (a rename would change the inode).
  const ino_t before = inode(file);
  { const ComputePipeline again(second, smoke_pipeline_desc()); }
  second.save_pipeline_cache();
  EXPECT_EQ(inode(file), before);
  // Whatever another specialization adds is on disk right after it is built.
  { const ComputePipeline other(second, smoke_pipeline_desc(32)); }
  EXPECT_TRUE(std::ranges::equal(decode_pipeline_cache_file(read_bytes(file)).payload, cache_data(second)));
}

// A file PipelineCacheTest::valid_file_bytes wrote, spoiled one way.
struct BadFile {
  std::string name;
  std::function<std::vector<std::byte>(const std::vector<std::byte>& valid)> spoil;
  std::string complaint;  // part of the warning line
};
void PrintTo(const BadFile& file, std::ostream* out) { *out << file.name; }  // not its bytes in test names

// The valid file with another key or payload, and a correct checksum: only the key check (or the
// check of the Vulkan header inside the payload) can tell.
std::vector<std::byte> reencoded(const std::vector<std::byte>& valid, const std::function<void(PipelineCacheKey&)>& change_key,
                                 const std::function<void(std::vector<std::byte>&)>& change_payload = {}) {
  const PipelineCacheFileContents contents = decode_pipeline_cache_file(valid);
  PipelineCacheKey key = contents.key;
  std::vector<std::byte> payload(contents.payload.begin(), contents.payload.end());
  change_key(key);
  if (change_payload) change_payload(payload);
  return encode_pipeline_cache_file(key, payload);
}
void keep(PipelineCacheKey&) {}

std::vector<BadFile> bad_files() {
  const auto cut = [](std::size_t keep_bytes) {
    return [keep_bytes](const std::vector<std::byte>& v) { return std::vector<std::byte>(v.begin(), v.begin() + keep_bytes); };
  };
  return {
      {"Empty", cut(0), "truncated: 0 bytes"},
      {"TruncatedInTheHeader", cut(40), "truncated: 40 bytes, shorter than the 92-byte header"},
      {"TruncatedInThePayload", [](const auto& v) { return std::vector<std::byte>(v.begin(), v.end() - 7); }, "truncated:"},
      {"Garbage",
       [](const auto& v) {
         std::mt19937 random(26);
         std::vector<std::byte> bytes(v.size());
         for (auto& b : bytes) b = std::byte(random() & 0xff);
         return bytes;
       },
       "no NUPC magic"},
      {"GarbageAfterAValidHeader",
       [](const auto& v) {
         auto bytes = v;
         for (std::size_t i = kPipelineCacheHeaderBytes; i < bytes.size(); ++i) bytes[i] = std::byte(i * 37);
         return bytes;
       },
       "checksum mismatch"},
      {"ForeignDriverVersion", [](const auto& v) { return reencoded(v, [](auto& k) { k.driver_version ^= 1; }); },
       "written for another driver version"},
      {"ForeignDeviceUuid", [](const auto& v) { return reencoded(v, [](auto& k) { k.device_uuid[3] ^= 0x10; }); },
       "written for another device UUID"},
      {"ForeignDriverUuid", [](const auto& v) { return reencoded(v, [](auto& k) { k.driver_uuid[0] ^= 0x01; }); },
       "written for another driver UUID"},
      {"ForeignVendor", [](const auto& v) { return reencoded(v, [](auto& k) { k.vendor_id = 0x10de; }); },
       "written for another vendor: 0x10de"},
      {"ForeignShaders", [](const auto& v) { return reencoded(v, [](auto& k) { k.shader_hash += 1; }); },
       "written for another build of the shaders"},
      {"PayloadOfAnotherVendor",
       [](const auto& v) { return reencoded(v, keep, [](auto& p) { p[8] = std::byte{0xde}, p[9] = std::byte{0x10}; }); },
       "driver data for another vendor: 0x"},
      {"PayloadOfAnotherPipelineCacheUuid",
       [](const auto& v) { return reencoded(v, keep, [](auto& p) { p[20] ^= std::byte{0xff}; }); },
       "driver data for another pipeline cache UUID"},
      {"PayloadHeaderVersionTwo", [](const auto& v) { return reencoded(v, keep, [](auto& p) { p[4] = std::byte{2}; }); },
       "Vulkan cache header version 2, expected 1"},
      {"PayloadHeaderSizeTooLarge",
       [](const auto& v) { return reencoded(v, keep, [](auto& p) { p[0] = std::byte{0xff}, p[1] = std::byte{0xff}; }); },
       "Vulkan cache header size"},
      {"PayloadShorterThanAVulkanHeader",
       [](const auto& v) { return reencoded(v, keep, [](auto& p) { p.resize(20); }); },
       "shorter than a Vulkan cache header"},
  };
}

class BadPipelineCacheFile : public PipelineCacheTest, public testing::WithParamInterface<BadFile> {};

// One warning line naming the file and what is wrong, an empty cache that works, and at the next
// save a sound file in place of the bad one.
TEST_P(BadPipelineCacheFile, IsIgnoredWithOneWarning) {
  fs::path file;
  const std::vector<std::byte> valid = valid_file_bytes(&file);
  write_bytes(file, GetParam().spoil(valid));

  std::string err;
  const Device device = open_device_capturing(err);
  const auto warnings = warning_lines(err);
  ASSERT_EQ(warnings.size(), 1u) << err;
  EXPECT_TRUE(warnings[0].starts_with("nanoview: warning: pipeline cache " + file.string() + ": ")) << warnings[0];
  EXPECT_NE(warnings[0].find(GetParam().complaint), std::string::npos) << warnings[0];
  EXPECT_TRUE(warnings[0].ends_with("; starting with an empty cache")) << warnings[0];
  EXPECT_LE(cache_data(device).size(), decode_pipeline_cache_file(valid).payload.size());

  testing::internal::CaptureStderr();
  { const ComputePipeline pipeline(device, smoke_pipeline_desc()); }
  EXPECT_TRUE(warning_lines(testing::internal::GetCapturedStderr()).empty());
  const auto replaced = decode_pipeline_cache_file(read_bytes(file));  // throws if still bad
  EXPECT_EQ(replaced.key, pipeline_cache_key(device.physical_device(), kShaderHash));
}

INSTANTIATE_TEST_SUITE_P(Vulkan, BadPipelineCacheFile, testing::ValuesIn(bad_files()),
                         [](const testing::TestParamInfo<BadFile>& info) { return info.param.name; });

// A rejected file that nothing replaces (no pipeline built) is still replaced when the device goes,
// so the warning comes once, not at every start.
TEST_F(PipelineCacheTest, RejectedFileIsReplacedEvenWhenNothingWasCompiled) {
  fs::path file;
  const std::vector<std::byte> valid = valid_file_bytes(&file);
  write_bytes(file, std::vector<std::byte>(10, std::byte{0}));
  std::string err;
  { const Device device = open_device_capturing(err); }
  EXPECT_EQ(warning_lines(err).size(), 1u) << err;
  { const Device device = open_device_capturing(err); }
  EXPECT_TRUE(warning_lines(err).empty()) << err;
}

TEST_F(PipelineCacheTest, UnreadableFileWarnsOnceAndTheRunGoesOn) {
  fs::path file;
  valid_file_bytes(&file);
  fs::remove(file);
  fs::create_directory(file);  // a folder where the file should be: opens, but cannot be read
  std::string err;
  const Device device = open_device_capturing(err);
  const auto warnings = warning_lines(err);
  ASSERT_EQ(warnings.size(), 1u) << err;
  EXPECT_NE(warnings[0].find("cannot read it: Is a directory; starting with an empty cache"), std::string::npos) << warnings[0];

  // Nor can it be replaced: saving warns once, then stops trying.
  testing::internal::CaptureStderr();
  { const ComputePipeline pipeline(device, smoke_pipeline_desc()); }
  { const ComputePipeline pipeline(device, smoke_pipeline_desc(32)); }
  err = testing::internal::GetCapturedStderr();
  const auto save_warnings = warning_lines(err);
  ASSERT_EQ(save_warnings.size(), 1u) << err;
  EXPECT_TRUE(save_warnings[0].starts_with("nanoview: warning: pipeline cache " + file.string() + ": cannot save it ("))
      << save_warnings[0];
  EXPECT_TRUE(save_warnings[0].ends_with("); compiled pipelines are not kept for the next run")) << save_warnings[0];
}

TEST_F(PipelineCacheTest, UnwritableCacheDirectoryWarnsOnce) {
  write_bytes(root_ / "xdg", std::vector<std::byte>(1, std::byte{0}));  // a file where the folder should be
  std::string err;
  const Device device = open_device_capturing(err);
  EXPECT_TRUE(warning_lines(err).empty()) << err;  // nothing to read is no reason to warn
  testing::internal::CaptureStderr();
  { const ComputePipeline pipeline(device, smoke_pipeline_desc()); }
  { const ComputePipeline pipeline(device, smoke_pipeline_desc(32)); }
  device.save_pipeline_cache();
  err = testing::internal::GetCapturedStderr();
  const auto warnings = warning_lines(err);
  ASSERT_EQ(warnings.size(), 1u) << err;
  EXPECT_NE(warnings[0].find(": cannot save it ("), std::string::npos) << warnings[0];
}

TEST_F(PipelineCacheTest, DisabledReadsAndWritesNothing) {
  fs::path file;
  valid_file_bytes(&file);
  write_bytes(file, std::vector<std::byte>(10, std::byte{0}));  // would warn if it were read
  const ino_t before = inode(file);
  testing::internal::CaptureStderr();
  {
    const Device device = open_device(false);
    EXPECT_EQ(device.pipeline_cache(), VK_NULL_HANDLE);
    const ComputePipeline pipeline(device, smoke_pipeline_desc(32));
    device.save_pipeline_cache();
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(warning_lines(err).empty()) << err;
  EXPECT_EQ(inode(file), before);
  EXPECT_EQ(read_bytes(file), std::vector<std::byte>(10, std::byte{0}));
  EXPECT_EQ(std::distance(fs::directory_iterator(file.parent_path()), fs::directory_iterator()), 1);
}

TEST_F(PipelineCacheTest, DisabledCreatesNoFolder) {
  {
    const Device device = open_device(false);
    const ComputePipeline pipeline(device, smoke_pipeline_desc());
  }
  EXPECT_FALSE(fs::exists(root_ / "xdg" / "nanouniverse"));
  EXPECT_FALSE(fs::exists(root_ / "home" / ".cache" / "nanouniverse"));
}

TEST_F(PipelineCacheTest, RelativeXdgCacheHomeIsIgnored) {
  const ScopedEnvironment relative("XDG_CACHE_HOME", "relative-cache");
  fs::path file;
  valid_file_bytes(&file);
  EXPECT_EQ(file.parent_path(), root_ / "home" / ".cache" / "nanouniverse");
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(fs::current_path() / "relative-cache"));
}

TEST_F(PipelineCacheTest, WithoutAnyCacheDirectoryPipelinesStillWork) {
  const ScopedEnvironment no_xdg("XDG_CACHE_HOME", std::nullopt);
  const ScopedEnvironment relative_home("HOME", "relative-home");
  std::string err;
  const Device device = open_device_capturing(err);
  const auto warnings = warning_lines(err);
  ASSERT_EQ(warnings.size(), 1u) << err;
  EXPECT_EQ(warnings[0],
            "nanoview: warning: pipeline cache: neither XDG_CACHE_HOME nor HOME is an absolute path; compiled pipelines "
            "are not kept across runs");
  EXPECT_NE(device.pipeline_cache(), VK_NULL_HANDLE) << "still shared within the run";
  testing::internal::CaptureStderr();
  { const ComputePipeline pipeline(device, smoke_pipeline_desc()); }
  EXPECT_TRUE(warning_lines(testing::internal::GetCapturedStderr()).empty());
  EXPECT_FALSE(fs::exists(fs::current_path() / "relative-home"));
}

// PipelineCache on its own: save() writes when the file does not hold the data yet, and only then.
TEST_F(PipelineCacheTest, SaveWritesOnlyWhatTheFileLacks) {
  const Device device = open_device(false);
  const PipelineCacheKey key = pipeline_cache_key(device.physical_device(), kShaderHash);
  const fs::path file = root_ / "own" / "cache.bin";
  {
    PipelineCache cache(device.handle(), key, file);
    EXPECT_EQ(cache.file(), file);
    EXPECT_NE(cache.handle(), VK_NULL_HANDLE);
    EXPECT_FALSE(fs::exists(file)) << "nothing is written before save()";
    EXPECT_TRUE(cache.save()) << "no file yet";
    EXPECT_FALSE(cache.save()) << "nothing new";
    const auto contents = decode_pipeline_cache_file(read_bytes(file));
    EXPECT_EQ(contents.key, key);
    EXPECT_TRUE(std::ranges::equal(contents.payload, cache.data()));
  }
  const ino_t before = inode(file);
  testing::internal::CaptureStderr();
  {
    PipelineCache loaded(device.handle(), key, file);
    EXPECT_FALSE(loaded.save()) << "the file holds what was loaded";
  }
  EXPECT_TRUE(warning_lines(testing::internal::GetCapturedStderr()).empty());
  EXPECT_EQ(inode(file), before) << "the destructor's save wrote nothing either";
}

// Pipelines built on two threads at once while a third saves: the file ends up with both.
TEST_F(PipelineCacheTest, ConcurrentPipelinesAndSaves) {
  const Device device = open_device();
  std::atomic<bool> done{false};
  std::thread saver([&] {
    while (!done) device.save_pipeline_cache();
  });
  {
    std::thread a([&] { const ComputePipeline p(device, smoke_pipeline_desc(32)); });
    std::thread b([&] { const ComputePipeline p(device, smoke_pipeline_desc(64)); });
    a.join();
    b.join();
  }
  done = true;
  saver.join();
  const auto on_disk = decode_pipeline_cache_file(read_bytes(cache_file_of(device)));
  EXPECT_TRUE(std::ranges::equal(on_disk.payload, cache_data(device)));

  // A fresh device loads both: building either adds nothing.
  const Device second = open_device();
  const ino_t before = inode(cache_file_of(second));
  { const ComputePipeline p(second, smoke_pipeline_desc(32)); }
  { const ComputePipeline p(second, smoke_pipeline_desc(64)); }
  EXPECT_EQ(inode(cache_file_of(second)), before);
}

}  // namespace
