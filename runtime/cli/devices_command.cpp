// `nanoview devices [--json]`: every Vulkan physical device, whether it can run the ray-query
// renderer (and if not, exactly what it lacks), and which one the renderer would pick.
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/cli/commands.hpp"
#include "runtime/vk/device_report.hpp"
#include "runtime/vk/device_selection.hpp"
#include "runtime/vk/error.hpp"
#include "runtime/vk/instance.hpp"

namespace nano::cli {
namespace {

struct Survey {
  std::vector<vk::DeviceReport> reports;
  std::optional<std::size_t> chosen;
  std::string selection_error;  // set when chosen is empty
};

Survey survey_all_devices() {
  vk::Instance instance(vk::InstanceOptions{.validation = vk::validation_requested_by_environment()});
  Survey survey;
  const auto devices = vk::enumerate_physical_devices(instance.handle());
  for (std::uint32_t i = 0; i < devices.size(); ++i) survey.reports.push_back(vk::survey_device(devices[i], i));
  try {
    survey.chosen = vk::choose_device(survey.reports, vk::device_override_from_environment());
  } catch (const vk::DeviceSelectionError& e) {
    survey.selection_error = e.what();
  }
  return survey;
}

nlohmann::json to_json(const Survey& survey) {
  nlohmann::json devices = nlohmann::json::array();
  for (std::size_t i = 0; i < survey.reports.size(); ++i) {
    const auto& r = survey.reports[i];
    devices.push_back({{"index", r.index},
                       {"name", r.name},
                       {"type", vk::device_type_name(r.type)},
                       {"api_version", vk::api_version_string(r.api_version)},
                       {"driver_name", r.driver_name},
                       {"driver_info", r.driver_info},
                       {"ray_query", r.qualifies()},
                       {"missing", r.missing},
                       {"shader_int64", r.shader_int64},
                       {"chosen", survey.chosen == i}});
  }
  nlohmann::json out{{"devices", devices}};
  out["chosen"] = survey.chosen ? nlohmann::json(survey.reports[*survey.chosen].index) : nlohmann::json(nullptr);
  if (!survey.chosen) out["error"] = survey.selection_error;
  return out;
}

void print_text(const Survey& survey) {
  for (std::size_t i = 0; i < survey.reports.size(); ++i) {
    const auto& r = survey.reports[i];
    std::string driver = r.driver_name.empty() ? std::string("driver unknown") : r.driver_name;
    if (!r.driver_info.empty()) driver += " " + r.driver_info;
    std::printf("%s [%u] %s\n", survey.chosen == i ? "*" : " ", r.index, r.name.c_str());
    std::printf("      type %s, driver %s, Vulkan %s\n", vk::device_type_name(r.type), driver.c_str(),
                vk::api_version_string(r.api_version).c_str());
    if (r.qualifies()) {
      std::printf("      ray queries: yes%s\n", r.shader_int64 ? " (shaderInt64 too)" : "");
    } else {
      std::printf("      ray queries: no, lacks");
      for (std::size_t m = 0; m < r.missing.size(); ++m) std::printf("%s %s", m ? "," : "", r.missing[m].c_str());
      std::printf("\n");
    }
  }
  if (survey.chosen) std::printf("* = chosen for rendering (override with NANO_DEVICE=<index or name>)\n");
}

}  // namespace

void add_devices_command(CLI::App& app) {
  auto* command = app.add_subcommand("devices", "List Vulkan devices and whether they can run the ray-query renderer");
  auto json = std::make_shared<bool>(false);
  command->add_flag("--json", *json, "Print a JSON document instead of text");
  command->callback([json] {
    const Survey survey = survey_all_devices();
    if (*json) {
      std::printf("%s\n", to_json(survey).dump(2).c_str());
    } else {
      print_text(survey);
    }
    if (!survey.chosen) {
      std::fprintf(stderr, "nanoview: error: %s\n", survey.selection_error.c_str());
      throw CLI::RuntimeError(1);
    }
  });
}

}  // namespace nano::cli
