#pragma once
// Which physical device the renderer uses: an explicit override (NANO_DEVICE), otherwise the first
// qualifying discrete GPU, then integrated, then virtual, then anything else (lavapipe is a CPU).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "runtime/vk/device_report.hpp"

namespace nano::vk {

// NANO_DEVICE=<index> or <case-insensitive substring of the device name>; nullopt when unset/empty.
std::optional<std::string> device_override_from_environment();

// Returns the position in `reports` of the chosen device. Throws DeviceSelectionError naming every
// device and exactly what it lacks when none qualifies, or when the override matches no device or
// a device that does not qualify.
std::size_t choose_device(const std::vector<DeviceReport>& reports, const std::optional<std::string>& override_spec);

// "[0] llvmpipe (CPU): lacks VK_KHR_ray_query, ..." per line, or "... : ready" when it qualifies.
std::string describe_devices(const std::vector<DeviceReport>& reports);

}  // namespace nano::vk
