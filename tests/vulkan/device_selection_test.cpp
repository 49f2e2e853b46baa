// The selection policy on synthetic device reports: no Vulkan device needed.
#include <gtest/gtest.h>

#include "runtime/vk/device_selection.hpp"
#include "runtime/vk/error.hpp"

namespace {

using nano::vk::DeviceReport;

DeviceReport device(std::uint32_t index, std::string name, VkPhysicalDeviceType type, std::vector<std::string> missing = {}) {
  DeviceReport report;
  report.index = index;
  report.name = std::move(name);
  report.type = type;
  report.api_version = VK_API_VERSION_1_3;
  report.compute_queue_family = 0;
  report.missing = std::move(missing);
  return report;
}

std::string selection_error(const std::vector<DeviceReport>& reports, const std::optional<std::string>& spec) {
  try {
    nano::vk::choose_device(reports, spec);
  } catch (const nano::vk::DeviceSelectionError& e) {
    return e.what();
  }
  ADD_FAILURE() << "choose_device did not throw";
  return {};
}

TEST(DeviceSelection, PrefersDiscreteThenIntegratedThenCpu) {
  const std::vector<DeviceReport> reports = {
      device(0, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU),
      device(1, "Intel UHD", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU),
      device(2, "NVIDIA GeForce RTX 4090", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
  };
  EXPECT_EQ(nano::vk::choose_device(reports, std::nullopt), 2u);
  EXPECT_EQ(nano::vk::choose_device({reports[0], reports[1]}, std::nullopt), 1u);
  EXPECT_EQ(nano::vk::choose_device({reports[0]}, std::nullopt), 0u);
}

TEST(DeviceSelection, SkipsDevicesThatLackRequirements) {
  const std::vector<DeviceReport> reports = {
      device(0, "Old GPU", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, {"VK_KHR_ray_query"}),
      device(1, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU),
  };
  EXPECT_EQ(nano::vk::choose_device(reports, std::nullopt), 1u);
}

TEST(DeviceSelection, OverrideByIndexOrCaseInsensitiveNameSubstring) {
  const std::vector<DeviceReport> reports = {
      device(0, "NVIDIA GeForce RTX 4090", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
      device(1, "llvmpipe (LLVM 15.0.6, 256 bits)", VK_PHYSICAL_DEVICE_TYPE_CPU),
  };
  EXPECT_EQ(nano::vk::choose_device(reports, std::string("1")), 1u);
  EXPECT_EQ(nano::vk::choose_device(reports, std::string("LLVMpipe")), 1u);
  EXPECT_EQ(nano::vk::choose_device(reports, std::string("rtx")), 0u);
}

TEST(DeviceSelection, OverrideThatMatchesNothingListsTheDevices) {
  const std::vector<DeviceReport> reports = {device(0, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU)};
  const std::string message = selection_error(reports, std::string("radeon"));
  EXPECT_NE(message.find("NANO_DEVICE=radeon matches no Vulkan device"), std::string::npos) << message;
  EXPECT_NE(message.find("[0] llvmpipe (CPU)"), std::string::npos) << message;
  EXPECT_NE(selection_error(reports, std::string("3")).find("matches no Vulkan device"), std::string::npos);
}

TEST(DeviceSelection, OverrideOfAnUnqualifiedDeviceSaysWhatItLacks) {
  const std::vector<DeviceReport> reports = {
      device(0, "Old GPU", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, {"VK_KHR_acceleration_structure"}),
      device(1, "llvmpipe", VK_PHYSICAL_DEVICE_TYPE_CPU),
  };
  const std::string message = selection_error(reports, std::string("old"));
  EXPECT_NE(message.find("[0] Old GPU (discrete GPU): lacks VK_KHR_acceleration_structure"), std::string::npos) << message;
}

TEST(DeviceSelection, NoQualifiedDeviceNamesEachDeviceAndEachMissingRequirement) {
  const std::vector<DeviceReport> reports = {
      device(0, "GPU A", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU,
             {"VK_KHR_ray_query", "VkPhysicalDeviceAccelerationStructureFeaturesKHR::accelerationStructure"}),
      device(1, "GPU B", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, {"Vulkan 1.2 (device offers 1.1.0)"}),
  };
  const std::string message = selection_error(reports, std::nullopt);
  EXPECT_NE(message.find("no Vulkan device supports ray queries"), std::string::npos) << message;
  EXPECT_NE(message.find("[0] GPU A (discrete GPU): lacks VK_KHR_ray_query, "
                         "VkPhysicalDeviceAccelerationStructureFeaturesKHR::accelerationStructure"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("[1] GPU B (integrated GPU): lacks Vulkan 1.2 (device offers 1.1.0)"), std::string::npos) << message;
}

TEST(DeviceSelection, NoDevicesAtAll) {
  EXPECT_NE(selection_error({}, std::nullopt).find("no Vulkan physical devices found"), std::string::npos);
}

}  // namespace
