#include "runtime/viewer/presenter.hpp"

#include <mutex>

#include <algorithm>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "runtime/viewer/progressive.hpp"
#include "runtime/vk/error.hpp"

namespace nano::viewer {
namespace {

using vk::check;

// 8-bit formats only: the renderer's words are copied byte for byte. UNORM first: the words are
// already sRGB-encoded, and an *_SRGB attachment would also re-encode the overlay's colours. An
// *_SRGB swapchain still shows the image right (a copy does not convert; the bytes are read as
// sRGB), only the overlay comes out lighter.
struct FormatChoice {
  VkFormat format;
  bool bgra;
};
constexpr FormatChoice kFormats[] = {
    {VK_FORMAT_B8G8R8A8_UNORM, true},
    {VK_FORMAT_R8G8B8A8_UNORM, false},
    {VK_FORMAT_B8G8R8A8_SRGB, true},
    {VK_FORMAT_R8G8B8A8_SRGB, false},
};

vk::DeviceHandle<VkSemaphore> make_semaphore(VkDevice d) {
  VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore semaphore = VK_NULL_HANDLE;
  check(vkCreateSemaphore(d, &semaphore_info, nullptr, &semaphore), "vkCreateSemaphore");
  return vk::DeviceHandle<VkSemaphore>(d, semaphore, vkDestroySemaphore);
}

// The swapchain's size for a framebuffer of fw × fh pixels; 0 × 0 while minimised on some platforms.
VkExtent2D swapchain_extent(const VkSurfaceCapabilitiesKHR& caps, std::uint32_t fw, std::uint32_t fh) {
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {  // the surface takes the swapchain's size
    extent.width = std::clamp(fw, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(fh, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  return extent;
}

VkCompositeAlphaFlagBitsKHR composite_alpha(const VkSurfaceCapabilitiesKHR& caps) {
  VkCompositeAlphaFlagBitsKHR alpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  if (!(caps.supportedCompositeAlpha & alpha))
    for (VkCompositeAlphaFlagBitsKHR a : {VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR, VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                          VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
      if (caps.supportedCompositeAlpha & a) {
        alpha = a;
        break;
      }
  return alpha;
}

}  // namespace

Presenter::Presenter(const vk::Device& device, VkSurfaceKHR surface, const Window& window)
    : device_(device), surface_(surface), window_(window) {
  choose_format();
  const VkDevice d = device_.handle();

  VkAttachmentDescription attachment{};
  attachment.format = format_;
  attachment.samples = VK_SAMPLE_COUNT_1_BIT;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // keep the uploaded frame under the overlay
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference colour{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colour;
  VkSubpassDependency dependencies[2]{};
  // The copy into the image happens before the overlay blends onto it.
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
  dependencies[1].dstAccessMask = 0;
  VkRenderPassCreateInfo pass_info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  pass_info.attachmentCount = 1;
  pass_info.pAttachments = &attachment;
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = 2;
  pass_info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  check(vkCreateRenderPass(d, &pass_info, nullptr, &pass), "vkCreateRenderPass");
  render_pass_ = vk::DeviceHandle<VkRenderPass>(d, pass, vkDestroyRenderPass);

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = device_.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  check(vkCreateCommandPool(d, &pool_info, nullptr, &pool), "vkCreateCommandPool");
  pool_ = vk::DeviceHandle<VkCommandPool>(d, pool, vkDestroyCommandPool);
  VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocate.commandPool = pool;
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(d, &allocate, &commands_), "vkAllocateCommandBuffers");

  acquired_ = make_semaphore(d);
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first frame has nothing to wait for
  VkFence fence = VK_NULL_HANDLE;
  check(vkCreateFence(d, &fence_info, nullptr, &fence), "vkCreateFence");
  done_ = vk::DeviceHandle<VkFence>(d, fence, vkDestroyFence);

  recreate();
}

Presenter::~Presenter() {
  const std::lock_guard queue_lock(device_.queue_mutex());
  vkDeviceWaitIdle(device_.handle());
  destroy_swapchain_objects();
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), swapchain_, nullptr);
}

void Presenter::choose_format() {
  const VkPhysicalDevice physical = device_.physical_device();
  std::uint32_t count = 0;
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface_, &count, nullptr), "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(count);
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface_, &count, formats.data()), "vkGetPhysicalDeviceSurfaceFormatsKHR");
  for (const FormatChoice& choice : kFormats)
    for (const auto& f : formats)
      if (f.format == choice.format && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
        format_ = f.format, colour_space_ = f.colorSpace, bgra_ = choice.bgra;
        return;
      }
  std::string offered;
  for (const auto& f : formats) offered += (offered.empty() ? "" : ", ") + std::to_string(int(f.format));
  throw std::runtime_error("the window surface offers no 8-bit BGRA/RGBA sRGB-nonlinear format (VkFormat values: " +
                           offered + ")");
}

void Presenter::destroy_swapchain_objects() {
  framebuffers_.clear();
  views_.clear();
  rendered_.clear();
  images_.clear();
}

bool Presenter::recreate() {
  const auto [fw, fh] = window_.framebuffer_size();
  if (fw == 0 || fh == 0) return false;
  {
    const std::lock_guard queue_lock(device_.queue_mutex());
    check(vkDeviceWaitIdle(device_.handle()), "vkDeviceWaitIdle");
  }

  VkSurfaceCapabilitiesKHR caps{};
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_.physical_device(), surface_, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw std::runtime_error("the window's swapchain images cannot be transfer destinations; the viewer uploads into them");
  const VkExtent2D extent = swapchain_extent(caps, fw, fh);
  if (extent.width == 0 || extent.height == 0) return false;  // minimised on some platforms
  std::uint32_t images = std::max(caps.minImageCount, 2u);
  if (caps.maxImageCount != 0) images = std::min(images, caps.maxImageCount);

  replace_swapchain(caps, extent, images);
  create_image_targets();
  const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
  if (staging_.size() != bytes)
    staging_ = vk::Buffer(device_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::HostVisible);
  min_image_count_ = images;
  stale_ = false;
  if (on_recreate) on_recreate(min_image_count_);
  return true;
}

void Presenter::replace_swapchain(const VkSurfaceCapabilitiesKHR& caps, VkExtent2D extent, std::uint32_t images) {
  const VkDevice d = device_.handle();
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = images;
  info.imageFormat = format_;
  info.imageColorSpace = colour_space_;
  info.imageExtent = extent;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;  // one queue does everything
  info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR) ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                                                                                          : caps.currentTransform;
  info.compositeAlpha = composite_alpha(caps);
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported; frames are slower than vsync anyway
  info.clipped = VK_TRUE;
  info.oldSwapchain = swapchain_;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  check(vkCreateSwapchainKHR(d, &info, nullptr, &swapchain), "vkCreateSwapchainKHR");
  destroy_swapchain_objects();
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(d, swapchain_, nullptr);
  swapchain_ = swapchain;
  extent_ = extent;
}

void Presenter::create_image_targets() {
  const VkDevice d = device_.handle();
  std::uint32_t count = 0;
  check(vkGetSwapchainImagesKHR(d, swapchain_, &count, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(count);
  check(vkGetSwapchainImagesKHR(d, swapchain_, &count, images_.data()), "vkGetSwapchainImagesKHR");
  for (VkImage image : images_) {
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format_;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    check(vkCreateImageView(d, &view_info, nullptr, &view), "vkCreateImageView");
    views_.emplace_back(d, view, vkDestroyImageView);
    VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb_info.renderPass = render_pass_.get();
    fb_info.attachmentCount = 1;
    fb_info.pAttachments = &view;
    fb_info.width = extent_.width;
    fb_info.height = extent_.height;
    fb_info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    check(vkCreateFramebuffer(d, &fb_info, nullptr, &framebuffer), "vkCreateFramebuffer");
    framebuffers_.emplace_back(d, framebuffer, vkDestroyFramebuffer);
    rendered_.push_back(make_semaphore(d));
  }
}

bool Presenter::present(std::span<const std::uint32_t> rgba, std::uint32_t width, std::uint32_t height,
                        const std::function<void(VkCommandBuffer)>& overlay) {
  const auto [fw, fh] = window_.framebuffer_size();
  if (fw == 0 || fh == 0) return false;  // minimised: nothing to show, keep the swapchain
  // The queue may be busy with a pipeline's first dispatch on a worker thread (a driver that compiles
  // at first use compiles there): then this present is skipped, the window keeps its last image and
  // the caller goes on handling input, rather than waiting for the compiler.
  const std::unique_lock queue_lock(device_.queue_mutex(), std::try_to_lock);
  if (!queue_lock.owns_lock()) return false;
  if (stale_ || fw != extent_.width || fh != extent_.height) {
    if (!recreate()) return false;
  }
  const std::optional<std::uint32_t> index = acquire_image();
  if (!index) return false;
  upload(rgba, width, height);
  record_frame(*index, overlay);
  submit_and_present(*index);
  return true;
}

std::optional<std::uint32_t> Presenter::acquire_image() {
  const VkDevice d = device_.handle();
  VkFence fence = done_.get();
  check(vkWaitForFences(d, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  std::uint32_t index = 0;
  VkResult acquired = vkAcquireNextImageKHR(d, swapchain_, UINT64_MAX, acquired_.get(), VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    stale_ = true;
    return std::nullopt;
  }
  if (acquired == VK_SUBOPTIMAL_KHR)
    stale_ = true;  // still presentable; re-created after this frame
  else
    check(acquired, "vkAcquireNextImageKHR");
  check(vkResetFences(d, 1, &fence), "vkResetFences");
  return index;
}

// Stretched to the swapchain and swizzled on the host: a few MB per frame, far below the cost
// of the ray-query frame itself, and no sampler or pipeline of our own to keep.
void Presenter::upload(std::span<const std::uint32_t> rgba, std::uint32_t width, std::uint32_t height) {
  std::span<const std::uint32_t> source = rgba;
  if (width != extent_.width || height != extent_.height) {
    scratch_ = resample_nearest(rgba, width, height, extent_.width, extent_.height);
    source = scratch_;
  }
  std::vector<std::uint32_t> upload(source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    const std::uint32_t w = source[i];
    upload[i] = bgra_ ? ((w & 0x0000FF00u) | ((w & 0xFFu) << 16) | ((w >> 16) & 0xFFu) | 0xFF000000u) : (w | 0xFF000000u);
  }
  staging_.write(std::as_bytes(std::span(upload)));
}

// The copy of the staging buffer into swapchain image `index`, then the overlay's render pass.
void Presenter::record_frame(std::uint32_t index, const std::function<void(VkCommandBuffer)>& overlay) {
  check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
  VkImageMemoryBarrier to_transfer{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  to_transfer.srcAccessMask = 0;
  to_transfer.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_transfer.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // every pixel is overwritten
  to_transfer.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_transfer.srcQueueFamilyIndex = to_transfer.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_transfer.image = images_[index];
  to_transfer.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  // Source stage TRANSFER chains with the acquire semaphore's wait stage (submit_and_present).
  vkCmdPipelineBarrier(commands_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &to_transfer);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyBufferToImage(commands_, staging_.handle(), images_[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);

  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = render_pass_.get();
  pass.framebuffer = framebuffers_[index].get();
  pass.renderArea.extent = extent_;
  vkCmdBeginRenderPass(commands_, &pass, VK_SUBPASS_CONTENTS_INLINE);
  if (overlay) overlay(commands_);
  vkCmdEndRenderPass(commands_);
  check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
}

void Presenter::submit_and_present(std::uint32_t index) {
  VkSemaphore wait = acquired_.get(), signal = rendered_[index].get();
  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &wait;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &signal;
  check(vkQueueSubmit(device_.queue(), 1, &submit, done_.get()), "vkQueueSubmit");

  VkPresentInfoKHR present_info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present_info.waitSemaphoreCount = 1;
  present_info.pWaitSemaphores = &signal;
  present_info.swapchainCount = 1;
  present_info.pSwapchains = &swapchain_;
  present_info.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(device_.queue(), &present_info);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
    stale_ = true;
  else
    check(presented, "vkQueuePresentKHR");
}

}  // namespace nano::viewer
