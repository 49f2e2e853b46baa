#pragma once
// Dear ImGui's lifetime in the viewer: context, GLFW and Vulkan backends (drawing inside the
// presenter's render pass), the font texture, and one ImGui frame per presented frame.
#include <cstdint>

#include <vulkan/vulkan.h>

#include "runtime/viewer/presenter.hpp"
#include "runtime/viewer/window.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/handle.hpp"

namespace nano::viewer {

class Overlay {
public:
  Overlay(const Window& window, VkInstance instance, const vk::Device& device, const Presenter& presenter);
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;
  ~Overlay();

  void begin_frame();  // backends' and ImGui's NewFrame: widgets may be issued after this
  void end_frame();    // ImGui::Render: the draw data for record()
  void record(VkCommandBuffer commands);  // inside the presenter's render pass
  void set_min_image_count(std::uint32_t count);

private:
  vk::DeviceHandle<VkDescriptorPool> pool_;
  bool frame_open_ = false;
};

}  // namespace nano::viewer
