#include "runtime/vk/instance.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "runtime/vk/error.hpp"

namespace nano::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool layer_available(const char* name) {
  std::uint32_t count = 0;
  check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
  std::vector<VkLayerProperties> layers(count);
  check(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

bool layer_offers_extension(const char* layer, const char* extension) {
  std::uint32_t count = 0;
  check(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr), "vkEnumerateInstanceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  check(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()), "vkEnumerateInstanceExtensionProperties");
  for (const auto& e : extensions)
    if (std::strcmp(e.extensionName, extension) == 0) return true;
  return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL report_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* counts = static_cast<ValidationCounts*>(user);
  const char* label = "warning";
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    counts->errors.fetch_add(1);
    label = "error";
  } else {
    counts->warnings.fetch_add(1);
  }
  std::fprintf(stderr, "vulkan validation %s: %s\n", label, data->pMessage ? data->pMessage : "(no message)");
  // VK_FALSE: the call that triggered the message proceeds, as the spec requires of applications.
  return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationCounts* counts) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = report_message;
  info.pUserData = counts;
  return info;
}

}  // namespace

bool validation_requested_by_environment() {
  const char* value = std::getenv("NANO_VALIDATION");
  return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

Instance::Instance(const InstanceOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = options.application_name.c_str();
  app.pEngineName = "nanouniverse";
  app.apiVersion = VK_API_VERSION_1_2;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  for (const auto& name : options.extensions) {
    // Named here rather than left to vkCreateInstance's bare VK_ERROR_EXTENSION_NOT_PRESENT.
    if (!layer_offers_extension(nullptr, name.c_str()))
      throw std::runtime_error("Vulkan instance extension " + name + " is not available from the loader/drivers");
    extensions.push_back(name.c_str());
  }
  VkDebugUtilsMessengerCreateInfoEXT messenger_create = messenger_info(counts_.get());
  // Synchronization validation catches missing barriers (e.g. after acceleration-structure builds),
  // which no driver-level check would report.
  VkValidationFeatureEnableEXT enabled_features[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  validation_features.enabledValidationFeatureCount = 1;
  validation_features.pEnabledValidationFeatures = enabled_features;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  if (options.validation) {
    if (!layer_available(kValidationLayer))
      throw std::runtime_error(std::string("validation requested but ") + kValidationLayer +
                               " is not installed (Debian package vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    if (std::find(options.extensions.begin(), options.extensions.end(), VK_EXT_DEBUG_UTILS_EXTENSION_NAME) ==
        options.extensions.end())
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    // Chaining the messenger info also reports problems inside vkCreateInstance/vkDestroyInstance.
    info.pNext = &messenger_create;
    if (layer_offers_extension(kValidationLayer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
      extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
      validation_features.pNext = info.pNext;
      info.pNext = &validation_features;
    }
  }
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  check(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");

  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr) {
      destroy();
      throw std::runtime_error("vkCreateDebugUtilsMessengerEXT is missing although VK_EXT_debug_utils was enabled");
    }
    messenger_create.pNext = nullptr;
    VkResult result = create(instance_, &messenger_create, nullptr, &messenger_);
    if (result != VK_SUCCESS) {
      destroy();
      throw VulkanError("vkCreateDebugUtilsMessengerEXT", result);
    }
  }
}

Instance::Instance(Instance&& other) noexcept
    : instance_(std::exchange(other.instance_, VK_NULL_HANDLE)),
      messenger_(std::exchange(other.messenger_, VK_NULL_HANDLE)),
      counts_(std::exchange(other.counts_, std::make_unique<ValidationCounts>())) {}

Instance& Instance::operator=(Instance&& other) noexcept {
  if (this != &other) {
    destroy();
    instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
    messenger_ = std::exchange(other.messenger_, VK_NULL_HANDLE);
    counts_ = std::exchange(other.counts_, std::make_unique<ValidationCounts>());
  }
  return *this;
}

Instance::~Instance() { destroy(); }

void Instance::destroy() {
  if (instance_ == VK_NULL_HANDLE) return;
  if (messenger_ != VK_NULL_HANDLE) {
    auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger) destroy_messenger(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

Surface::Surface(Surface&& other) noexcept
    : instance_(std::exchange(other.instance_, VK_NULL_HANDLE)), surface_(std::exchange(other.surface_, VK_NULL_HANDLE)) {}

Surface& Surface::operator=(Surface&& other) noexcept {
  if (this != &other) {
    this->~Surface();
    instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
    surface_ = std::exchange(other.surface_, VK_NULL_HANDLE);
  }
  return *this;
}

Surface::~Surface() {
  if (surface_ != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  surface_ = VK_NULL_HANDLE;
}

}  // namespace nano::vk
