// Issue #2 item 3: one sphere in a BLAS of AABBs under a rotated and translated TLAS instance,
// traced by shaders/smoke_ray_query.comp with the validation layer on, checked against analytic
// geometry in extended precision. Fails (never skips) when no ray-query device exists.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "runtime/vk/acceleration_structure.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/instance.hpp"
#include "shared/smoke_ray_query.h"
#include "tests/vulkan/sphere_oracle.hpp"

extern const uint32_t nano_spv_smoke_ray_query_comp[];
extern const std::size_t nano_spv_smoke_ray_query_comp_words;

namespace {

using GpuHit = nano::gpu::SmokeHit;
using GpuRay = nano::gpu::SmokeRay;

constexpr double kRadius = 1.5;
constexpr glm::dvec3 kObjectCentre{0.25, -0.5, 0.75};
constexpr std::uint32_t kCustomIndex = 7;
constexpr double kRelativeTolerance = 1e-5;
constexpr double kSilhouetteBand = 1e-4;  // hit/miss is not judged this close to the silhouette
constexpr std::uint32_t kWorkgroupSize = 64;

// Not identity: a translation, a rotation about z (axis-aligned z rays stay axis-aligned in object
// space, so zero direction components reach the BLAS traversal too) and a uniform scale (the
// object-space direction is then not the world one, yet t must be the same).
constexpr double kScale = 1.25;
constexpr double kWorldRadius = kRadius * kScale;
glm::dmat4 instance_transform() {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, -2.0, 5.0));
  m = glm::rotate(m, glm::radians(30.0), glm::dvec3(0, 0, 1));
  return glm::scale(m, glm::dvec3(kScale));
}

// The GPU sees the transform rounded to float; the oracle must place the sphere with that one.
glm::dvec3 world_centre_as_seen_by_gpu() {
  const VkTransformMatrixKHR m = nano::vk::to_transform_matrix(instance_transform());
  glm::dvec3 c;
  for (int row = 0; row < 3; ++row)
    c[row] = double(m.matrix[row][0]) * kObjectCentre.x + double(m.matrix[row][1]) * kObjectCentre.y +
             double(m.matrix[row][2]) * kObjectCentre.z + double(m.matrix[row][3]);
  return c;
}

struct RayCase {
  std::string name;
  GpuRay ray;
};

GpuRay make_ray(glm::dvec3 origin, glm::dvec3 direction, double t_min = 0.0, double t_max = 1e4) {
  return GpuRay{glm::vec4(glm::vec3(origin), float(t_min)), glm::vec4(glm::vec3(direction), float(t_max))};
}

std::vector<RayCase> ray_cases(const glm::dvec3& centre) {
  const double r = kWorldRadius;
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  std::vector<RayCase> cases = {
      {"through centre along -z (zero x,y)", make_ray(centre + 10.0 * z, -z)},
      {"through centre along +x, |d|=2 (zero y,z)", make_ray(centre - 8.0 * x, 2.0 * x)},
      {"through centre along -y (zero x,z)", make_ray(centre + 6.0 * y, -y)},
      {"through centre diagonal", make_ray(centre - glm::dvec3(4, 5, 6), glm::dvec3(4, 5, 6) * 0.25)},
      {"grazing just inside", make_ray(centre - 8.0 * x + r * (1 - 1e-3) * y, x)},
      {"grazing just outside", make_ray(centre - 8.0 * x + r * (1 + 1e-3) * y, x)},
      {"grazing inside along z", make_ray(centre + 9.0 * z + r * (1 - 2e-3) * glm::normalize(x + y), -z)},
      {"grazing outside along z", make_ray(centre + 9.0 * z + r * (1 + 2e-3) * glm::normalize(x - y), -z)},
      {"on the silhouette (not judged)", make_ray(centre - 8.0 * x + r * (1 + 3e-5) * z, x)},
      {"miss, pointing away", make_ray(centre + 5.0 * z, z)},
      {"miss, passing wide", make_ray(centre + glm::dvec3(-10, 4, 0), x)},
      {"starts inside", make_ray(centre + glm::dvec3(0.3, 0.2, -0.1), y)},
      {"starts at centre, |d|=0.5", make_ray(centre, glm::dvec3(0, 0, -0.5))},
      {"t_max ends before the sphere", make_ray(centre + 10.0 * z, -z, 0.0, 8.0)},
      {"t_min past the entry point", make_ray(centre + 10.0 * z, -z, 9.0, 1e4)},
      {"t_min past the exit point", make_ray(centre + 10.0 * z, -z, 10.0 + r + 0.1, 1e4)},
  };
  // Random rays from a shell around the sphere at random points of a box 1.3 r around it, so
  // hits, misses and near-silhouette rays all occur. A fixed seed keeps failures reproducible.
  std::mt19937 random(20240601u);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 512; ++i) {
    glm::dvec3 away;
    do away = glm::dvec3(unit(random), unit(random), unit(random));
    while (glm::length(away) < 0.1 || glm::length(away) > 1.0);
    const glm::dvec3 origin = centre + 12.0 * glm::normalize(away);
    const glm::dvec3 target = centre + 1.3 * r * glm::dvec3(unit(random), unit(random), unit(random));
    cases.push_back({"random " + std::to_string(i), make_ray(origin, (target - origin) * (0.5 + 0.5 * (unit(random) + 1.0)))});
  }
  return cases;
}

// Traces `rays` through a one-sphere scene; returns one hit record per ray.
std::vector<GpuHit> trace(const nano::vk::Device& device, const std::vector<GpuRay>& rays) {
  using namespace nano::vk;
  const VkAabbPositionsKHR aabb{float(kObjectCentre.x - kRadius), float(kObjectCentre.y - kRadius),
                                float(kObjectCentre.z - kRadius), float(kObjectCentre.x + kRadius),
                                float(kObjectCentre.y + kRadius), float(kObjectCentre.z + kRadius)};
  const Buffer aabbs = Buffer::with_data(device, std::as_bytes(std::span(&aabb, 1)), kBuildInputUsage, MemoryUse::DeviceLocal);
  const AccelerationStructure blas = build_bottom_level(device, AabbGeometry{aabbs.address(), 1});
  const VkAccelerationStructureInstanceKHR instance = make_instance(blas, instance_transform(), kCustomIndex);
  const AccelerationStructure tlas = build_top_level(device, std::span(&instance, 1));

  const glm::vec4 sphere{glm::vec3(kObjectCentre), float(kRadius)};  // object-space centre, radius
  const Buffer sphere_buffer = Buffer::with_data(device, std::as_bytes(std::span(&sphere, 1)),
                                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::DeviceLocal);
  const Buffer ray_buffer =
      Buffer::with_data(device, std::as_bytes(std::span(rays)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::DeviceLocal);
  Buffer hit_buffer(device, rays.size() * sizeof(GpuHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::HostVisible);

  ComputePipelineDesc desc;
  desc.code = {nano_spv_smoke_ray_query_comp, nano_spv_smoke_ray_query_comp_words};
  desc.sets = {{{0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
                {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}}};
  desc.push_constant_bytes = sizeof(std::uint32_t);
  desc.specialization.set(nano::gpu::kSmokeWorkgroupSizeConstantId, kWorkgroupSize);
  const ComputePipeline pipeline(device, desc);
  DescriptorPool pool(device, pipeline);
  const VkDescriptorSet set = pool.allocate(pipeline.set_layout(0));
  write_acceleration_structure(device.handle(), set, 0, tlas);
  write_storage_buffer(device.handle(), set, 1, ray_buffer);
  write_storage_buffer(device.handle(), set, 2, sphere_buffer);
  write_storage_buffer(device.handle(), set, 3, hit_buffer);

  const std::uint32_t ray_count = static_cast<std::uint32_t>(rays.size());
  device.submit_once([&](VkCommandBuffer commands) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(commands, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(ray_count), &ray_count);
    vkCmdDispatch(commands, (ray_count + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                         nullptr, 0, nullptr);
  });

  std::vector<GpuHit> hits(rays.size());
  hit_buffer.read(std::as_writable_bytes(std::span(hits)));
  return hits;
}


TEST(VulkanSmoke, OneSphereUnderTransformedInstanceMatchesAnalyticGeometry) {
  nano::vk::Instance instance(nano::vk::InstanceOptions{.validation = true});
  ASSERT_TRUE(instance.validation_enabled());
  {
    // Throws, and so fails the test, when no device supports ray queries: CI always has lavapipe.
    const nano::vk::Device device = nano::vk::open_ray_query_device(instance);
    std::printf("Vulkan device: %s\n", device.description().c_str());
    std::fflush(stdout);

    const glm::dvec3 centre = world_centre_as_seen_by_gpu();
    const std::vector<RayCase> cases = ray_cases(centre);
    std::vector<GpuRay> rays;
    for (const auto& c : cases) rays.push_back(c.ray);
    const std::vector<GpuHit> hits = trace(device, rays);

    int judged = 0, unjudged = 0, hit_count = 0;
    double worst_relative_error = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const GpuRay& ray = cases[i].ray;
      const auto answer = nano::test::intersect_sphere(glm::dvec3(glm::vec3(ray.origin_tmin)), glm::dvec3(glm::vec3(ray.direction_tmax)), centre, kWorldRadius,
                                                       ray.origin_tmin.w, ray.direction_tmax.w);
      const GpuHit& hit = hits[i];
      const bool gpu_hit = hit.t >= 0.0f;
      SCOPED_TRACE(cases[i].name);
      if (answer.silhouette_distance < kSilhouetteBand) {
        ++unjudged;
        continue;
      }
      ++judged;
      if (gpu_hit != answer.t.has_value()) {
        ADD_FAILURE() << (gpu_hit ? "GPU hit, reference misses" : "GPU misses, reference hits") << ": gpu t=" << hit.t
                      << " reference t=" << (answer.t ? *answer.t : -1.0);
        continue;
      }
      if (!gpu_hit) {
        EXPECT_EQ(hit.instance_custom_index, ~0u);
        continue;
      }
      ++hit_count;
      const double error = std::fabs(hit.t - *answer.t);
      worst_relative_error = std::max(worst_relative_error, error / std::max(std::fabs(*answer.t), 1.0));
      EXPECT_LE(error, kRelativeTolerance * std::max(std::fabs(*answer.t), 1.0))
          << "gpu t=" << hit.t << " reference t=" << *answer.t;
      EXPECT_EQ(hit.instance_custom_index, kCustomIndex);
      EXPECT_EQ(hit.instance_id, 0u);
      EXPECT_EQ(hit.primitive_id, 0u);
    }
    std::printf("rays: %zu, judged %d (%d hits), within %.0e of the silhouette %d, worst relative t error %.3g\n",
                cases.size(), judged, hit_count, kSilhouetteBand, unjudged, worst_relative_error);
    EXPECT_GT(hit_count, 20);
    EXPECT_GT(judged - hit_count, 20);
  }
  // After the device is gone, so messages from teardown count too.
  EXPECT_EQ(instance.validation_errors(), 0u);
  EXPECT_EQ(instance.validation_warnings(), 0u);
}

}  // namespace

// top_level_size names the storage build_top_level allocates for as many instances (the flat
// level budgets its memory with it before building).
TEST(VulkanSmoke, TopLevelSizeIsWhatTheBuildTakes) {
  using namespace nano::vk;
  Instance instance(InstanceOptions{.validation = true});
  {
    const Device device = open_ray_query_device(instance);
    const VkAabbPositionsKHR aabb{-1, -1, -1, 1, 1, 1};
    const Buffer aabbs = Buffer::with_data(device, std::as_bytes(std::span(&aabb, 1)), kBuildInputUsage, MemoryUse::DeviceLocal);
    const AccelerationStructure blas = build_bottom_level(device, AabbGeometry{aabbs.address(), 1});
    VkDeviceSize previous = 0;
    for (const std::uint32_t n : {1u, 7u, 1000u}) {
      std::vector<VkAccelerationStructureInstanceKHR> instances;
      for (std::uint32_t i = 0; i < n; ++i) {
        glm::dmat4 m(1.0);
        m[3] = glm::dvec4(3.0 * i, 0.0, 0.0, 1.0);
        instances.push_back(make_instance(blas, m, i));
      }
      const AccelerationStructure tlas = build_top_level(device, std::span(instances));
      EXPECT_EQ(top_level_size(device, n), tlas.size()) << n << " instances";
      EXPECT_GE(tlas.size(), previous);
      previous = tlas.size();
    }
  }
  EXPECT_EQ(instance.validation_errors(), 0u);
}
