#include "runtime/vk/device_selection.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>

#include "runtime/vk/error.hpp"

namespace nano::vk {
namespace {

int type_preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string describe_device(const DeviceReport& report) {
  std::string line = "[" + std::to_string(report.index) + "] " + report.name + " (" + device_type_name(report.type) + ")";
  if (report.qualifies()) return line + ": ready for ray queries";
  line += ": lacks ";
  for (std::size_t i = 0; i < report.missing.size(); ++i) line += (i ? ", " : "") + report.missing[i];
  return line;
}

std::optional<std::size_t> match_override(const std::vector<DeviceReport>& reports, const std::string& spec) {
  std::uint32_t index = 0;
  const auto [end, error] = std::from_chars(spec.data(), spec.data() + spec.size(), index);
  if (error == std::errc() && end == spec.data() + spec.size()) {
    for (std::size_t i = 0; i < reports.size(); ++i)
      if (reports[i].index == index) return i;
    return std::nullopt;
  }
  const std::string needle = lowercase(spec);
  for (std::size_t i = 0; i < reports.size(); ++i)
    if (lowercase(reports[i].name).find(needle) != std::string::npos) return i;
  return std::nullopt;
}

}  // namespace

std::optional<std::string> device_override_from_environment() {
  const char* value = std::getenv("NANO_DEVICE");
  if (value == nullptr || value[0] == '\0') return std::nullopt;
  return std::string(value);
}

std::string describe_devices(const std::vector<DeviceReport>& reports) {
  if (reports.empty()) return "no Vulkan physical devices found (is a Vulkan driver such as mesa-vulkan-drivers installed?)";
  std::string text;
  for (const auto& report : reports) text += (text.empty() ? "" : "\n") + describe_device(report);
  return text;
}

std::size_t choose_device(const std::vector<DeviceReport>& reports, const std::optional<std::string>& override_spec) {
  if (override_spec) {
    const auto match = match_override(reports, *override_spec);
    if (!match)
      throw DeviceSelectionError("NANO_DEVICE=" + *override_spec + " matches no Vulkan device; devices:\n" +
                                 describe_devices(reports));
    if (!reports[*match].qualifies())
      throw DeviceSelectionError("NANO_DEVICE=" + *override_spec + " selects a device that cannot run ray queries:\n" +
                                 describe_device(reports[*match]));
    return *match;
  }
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    if (!reports[i].qualifies()) continue;
    if (!best || type_preference(reports[i].type) < type_preference(reports[*best].type)) best = i;
  }
  if (!best) throw DeviceSelectionError("no Vulkan device supports ray queries:\n" + describe_devices(reports));
  return *best;
}

}  // namespace nano::vk
