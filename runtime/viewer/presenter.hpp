#pragma once
// Shows host images in the window: a swapchain on the window's surface, each frame's RGBA8 image
// uploaded through a staging buffer into the acquired swapchain image (vkCmdCopyBufferToImage,
// bytes swizzled to the swapchain's channel order), then one render pass that only loads that
// image and lets the caller draw an overlay (the ImGui panel) on top. Everything runs on the
// device's one queue, one frame in flight: the renderer already waits for each frame on the host.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/buffer.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/handle.hpp"
#include "runtime/viewer/window.hpp"

namespace nano::viewer {

class Presenter {
public:
  // Throws std::runtime_error when the surface offers no 8-bit RGBA/BGRA format or cannot be a
  // transfer destination (the upload needs both).
  Presenter(const vk::Device& device, VkSurfaceKHR surface, const Window& window);
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;
  ~Presenter();

  VkRenderPass overlay_pass() const { return render_pass_.get(); }
  std::uint32_t min_image_count() const { return min_image_count_; }
  std::uint32_t image_count() const { return std::uint32_t(images_.size()); }
  // Called after each swapchain re-creation with the new minimum image count (ImGui needs it).
  std::function<void(std::uint32_t)> on_recreate;

  // `rgba`: width × height words, RGBA8 sRGB-encoded, R in the low byte, row 0 at the top; it is
  // stretched (nearest) to the swapchain's extent. `overlay` records draws inside the render pass.
  // Returns false when nothing was shown: the window is minimised, or the swapchain was out of
  // date and has been re-created (the caller simply tries again next frame).
  bool present(std::span<const std::uint32_t> rgba, std::uint32_t width, std::uint32_t height,
               const std::function<void(VkCommandBuffer)>& overlay);

private:
  void choose_format();
  bool recreate();  // false while the window has no area
  void replace_swapchain(const VkSurfaceCapabilitiesKHR& caps, VkExtent2D extent, std::uint32_t images);
  void create_image_targets();  // per swapchain image: its view, framebuffer and `rendered_` semaphore
  void destroy_swapchain_objects();
  std::optional<std::uint32_t> acquire_image();  // none when the swapchain is out of date
  void upload(std::span<const std::uint32_t> rgba, std::uint32_t width, std::uint32_t height);
  void record_frame(std::uint32_t index, const std::function<void(VkCommandBuffer)>& overlay);
  void submit_and_present(std::uint32_t index);

  const vk::Device& device_;
  VkSurfaceKHR surface_;
  const Window& window_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR colour_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  bool bgra_ = true;  // swapchain byte order B, G, R, A
  std::uint32_t min_image_count_ = 2;
  VkExtent2D extent_{0, 0};
  bool stale_ = true;  // re-create before the next frame

  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  std::vector<VkImage> images_;
  std::vector<vk::DeviceHandle<VkImageView>> views_;
  std::vector<vk::DeviceHandle<VkFramebuffer>> framebuffers_;
  std::vector<vk::DeviceHandle<VkSemaphore>> rendered_;  // per image: presentation may still wait on it
  vk::DeviceHandle<VkRenderPass> render_pass_;
  vk::DeviceHandle<VkCommandPool> pool_;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  vk::DeviceHandle<VkSemaphore> acquired_;
  vk::DeviceHandle<VkFence> done_;
  vk::Buffer staging_;
  std::vector<std::uint32_t> scratch_;
};

}  // namespace nano::viewer
