#include "runtime/viewer/overlay.hpp"

#include <algorithm>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include "runtime/vk/error.hpp"

namespace nano::viewer {
namespace {

void check_imgui_result(VkResult result) {
  // Called from inside the backend (C++ code, so unwinding through it is fine).
  if (result != VK_SUCCESS) throw vk::VulkanError("ImGui Vulkan backend", result);
}

}  // namespace

Overlay::Overlay(const Window& window, VkInstance instance, const vk::Device& device, const Presenter& presenter) {
  const VkDevice d = device.handle();
  // The font atlas is the only texture; a few sets of headroom.
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool_info.maxSets = 8;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  vk::check(vkCreateDescriptorPool(d, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
  pool_ = vk::DeviceHandle<VkDescriptorPool>(d, pool, vkDestroyDescriptorPool);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in whatever directory the viewer (or a test) runs in
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window.handle(), true);

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = instance;
  info.PhysicalDevice = device.physical_device();
  info.Device = d;
  info.QueueFamily = device.queue_family();
  info.Queue = device.queue();
  info.DescriptorPool = pool;
  info.Subpass = 0;
  info.MinImageCount = std::max(presenter.min_image_count(), 2u);
  info.ImageCount = std::max(presenter.image_count(), info.MinImageCount);
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = check_imgui_result;
  ImGui_ImplVulkan_Init(&info, presenter.overlay_pass());
  device.submit_once([](VkCommandBuffer commands) { ImGui_ImplVulkan_CreateFontsTexture(commands); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Overlay::~Overlay() {
  vkDeviceWaitIdle(pool_.device());  // the last presented frame may still sample the font atlas
  if (frame_open_) ImGui::EndFrame();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Overlay::begin_frame() {
  if (frame_open_) ImGui::EndFrame();  // a frame abandoned by an exception or a skipped present
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  frame_open_ = true;
}

void Overlay::end_frame() {
  ImGui::Render();
  frame_open_ = false;
}

void Overlay::record(VkCommandBuffer commands) {
  if (ImDrawData* data = ImGui::GetDrawData()) ImGui_ImplVulkan_RenderDrawData(data, commands);
}

void Overlay::set_min_image_count(std::uint32_t count) { ImGui_ImplVulkan_SetMinImageCount(std::max(count, 2u)); }

}  // namespace nano::viewer
