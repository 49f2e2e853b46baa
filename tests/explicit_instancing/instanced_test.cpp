// Explicit instancing (one TLAS instance per molecule copy) against virtual instancing (nested ray
// queries) on the bundled virion: both are exact renderers of the same scene, so they must show the
// same atom of the same copy at the same depth in (nearly) every pixel.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "format/package_view.hpp"
#include "format/writer.hpp"
#include "format/validator.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "runtime/oracle/verify_cameras.hpp"
#include "runtime/explicit_instancing/explicit_vs_virtual.hpp"
#include "runtime/explicit_instancing/instanced_renderer.hpp"
#include "runtime/explicit_instancing/instanced_scene.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/vk/device.hpp"
#include "shared/ray_counters.h"
#include "tests/oracle/hand_scene.hpp"
#include "tests/oracle/test_package.hpp"
#include "runtime/vk/instance.hpp"

namespace nano::explicit_instancing {
namespace {

// One package, device and virtual scene for every test of the process (opening them dominates).
struct Session {
  format::Package package = format::open_validated(NANO_VIRION_PACKAGE);
  // Under NANO_VALIDATION=1 (as CTest runs it) the Khronos layer checks every call; tests fail on its errors.
  vk::Instance instance{vk::InstanceOptions{.validation = vk::validation_requested_by_environment()}};
  vk::Device device = vk::open_ray_query_device(instance);
  std::unique_ptr<render::GpuScene> virtual_scene = std::make_unique<render::GpuScene>(device, package);
  ~Session() { virtual_scene.reset(); }  // before the device
};

Session& session() {
  static Session s;
  return s;
}

class Instanced : public ::testing::Test {
protected:
  void TearDown() override { EXPECT_EQ(session().instance.validation_errors(), 0u) << "validation-layer errors"; }
};

// The package's own camera and a few of verify's close views (grazing membrane, core, inside an atom).
std::vector<gpu::Camera> views(std::uint32_t size, std::size_t close_views) {
  Session& s = session();
  std::vector<gpu::Camera> cameras{render::package_camera(s.package).to_gpu(size, size)};
  const oracle::ExplicitScene oracle_scene(s.package);
  for (const oracle::VerifyCamera& v : oracle::verify_cameras(s.package, oracle_scene, close_views))
    cameras.push_back(v.view.to_gpu(size, size));
  return cameras;
}

std::uint64_t hit_pixels(const std::vector<gpu::PixelHit>& hits) {
  std::uint64_t n = 0;
  for (const gpu::PixelHit& h : hits) n += h.atom != gpu::kNoHit;
  return n;
}

void expect_agreement(InstancedRenderer& explicit_renderer, render::Renderer& virtual_renderer, const gpu::Camera& camera,
                      const std::string& name) {
  const InstancedFrame e = explicit_renderer.render(camera);
  const render::Frame v = virtual_renderer.render(camera);
  const oracle::CompareResult a = compare_hits(v.hits, e.hits);
  std::printf("%s: %llu/%llu agree (missed %llu, other atom %llu, depth %llu, max |Δt| %.3g Å), %llu hit pixels; "
              "explicit %.3f s, virtual %.3f s\n",
              name.c_str(), (unsigned long long)a.agree, (unsigned long long)a.pixels, (unsigned long long)a.missed,
              (unsigned long long)a.different_atom, (unsigned long long)a.depth_only, a.max_depth_difference,
              (unsigned long long)hit_pixels(v.hits), e.seconds, v.seconds);
  EXPECT_GE(a.agreement(), 0.999) << name;
  // Explicit instancing names only the atom and the copy; the placement ids stay unknown.
  for (const gpu::PixelHit& h : e.hits) {
    ASSERT_EQ(h.compartment_instance, gpu::kNoHit);
    ASSERT_EQ(h.kind, gpu::kNoHit);
  }
}

TEST_F(Instanced, VirionAgreesWithVirtualRenderer) {
  Session& s = session();
  InstancedScene scene(s.device, s.package);
  const InstancedReport& r = scene.report();
  std::printf("explicit scene: %s\n", to_json(r).dump().c_str());
  EXPECT_GT(r.copies, 0u);
  EXPECT_GT(r.instances, 0u);
  EXPECT_EQ(r.memory.instance_buffer, r.instances * 64);
  EXPECT_EQ(r.memory.copy_records, r.instances * 16);
  EXPECT_GT(r.memory.blas, 0u);
  EXPECT_GT(r.memory.tlas, 0u);
  EXPECT_GT(r.memory.atoms, 0u);
  InstancedRenderer explicit_renderer(s.device, scene);
  render::Renderer virtual_renderer(s.device, *s.virtual_scene);
  const std::vector<gpu::Camera> cameras = views(64, 4);
  for (std::size_t i = 0; i < cameras.size(); ++i)
    expect_agreement(explicit_renderer, virtual_renderer, cameras[i], "view " + std::to_string(i));
  // The package's view shows molecules, so agreement is not just background against background.
  EXPECT_GT(hit_pixels(explicit_renderer.render(cameras[0]).hits), 64u * 64u / 10);
}

// A package whose replication areas all fit NANO_DIRECT_SLOTS (the virion's are 2×2) gets the
// pipeline without the repLAS traversal; one with a larger area (the hand scene's 6×6) gets it and
// walks its large triangles through it — and both draw what explicit instancing draws.
TEST_F(Instanced, ReplicationAreaSizeSelectsTheRepLasTraversal) {
  Session& s = session();
  EXPECT_FALSE(s.virtual_scene->has_large_replication_areas());
  render::Renderer virion_renderer(s.device, *s.virtual_scene);
  EXPECT_NE(virion_renderer.pipeline_build().variant.find("small_areas"), std::string::npos) << virion_renderer.pipeline_build().variant;

  // The hand scene's prisms widened to its molecules' reach (1 Å sides, 2.7 Å molecules): the renderer
  // looks for a triangle's copies only inside its prism, as the baker's shells guarantee (a copy
  // centred on a shared edge lost its far half, in 4 of 4096 pixels, with the narrow sides).
  format::test::SampleScene scene = explicit_test::hand_scene();
  for (gpu::TriangleShell& shell : scene.triangle_shells) shell.side_offset = 4.0f;
  const explicit_test::TestPackage hand(scene);
  render::GpuScene hand_scene(s.device, hand.package);
  EXPECT_TRUE(hand_scene.has_large_replication_areas());
  render::Renderer hand_renderer(s.device, hand_scene, render::RenderSettings{.counters = true});
  EXPECT_EQ(hand_renderer.pipeline_build().variant.find("small_areas"), std::string::npos) << hand_renderer.pipeline_build().variant;
  InstancedScene explicit_scene(s.device, hand.package);
  InstancedRenderer explicit_renderer(s.device, explicit_scene);
  // Straight down onto the flat membranes, and grazing them.
  for (const char* view : {"position=64,64,140;look_at=64,64,0;up=0,1,0;fov=60", "position=-60,70,9;look_at=64,64,0;up=0,0,1;fov=50"}) {
    const gpu::Camera camera = render::parse_camera(view, {}, "--camera").to_gpu(64, 64);
    expect_agreement(explicit_renderer, hand_renderer, camera, view);
    const render::Frame counted = hand_renderer.render(camera);
    std::uint64_t replas_queries = 0;
    for (std::size_t p = 0; p < counted.hits.size(); ++p) replas_queries += counted.counters[p * gpu::NANO_RAY_COUNTER_COUNT + gpu::NANO_RC_REPLAS_QUERIES];
    EXPECT_GT(replas_queries, 0u) << view << ": no prism walked its slots through the repLAS";
  }
}

// The TLAS rebuilt relative to each eye (as GpuScene::set_eye) renders the same pixels.
TEST_F(Instanced, EyeRelativeTlasAgrees) {
  Session& s = session();
  InstancedScene scene(s.device, s.package, InstancedOptions{.eye_relative = true});
  InstancedRenderer explicit_renderer(s.device, scene);
  render::Renderer virtual_renderer(s.device, *s.virtual_scene);
  const std::vector<gpu::Camera> cameras = views(64, 2);
  for (std::size_t i = 0; i < cameras.size(); ++i)
    expect_agreement(explicit_renderer, virtual_renderer, cameras[i], "eye-relative view " + std::to_string(i));
}

TEST_F(Instanced, RefusesMoreCopiesThanTheLimit) {
  Session& s = session();
  try {
    InstancedScene scene(s.device, s.package, InstancedOptions{.max_copies = 10});
    FAIL() << "a scene of more than 10 copies was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(s.package.name()), std::string::npos) << what;
    EXPECT_NE(what.find("more than 10 molecule copies"), std::string::npos) << what;
    EXPECT_NE(what.find("virtual instancing"), std::string::npos) << what;
  }
  EXPECT_THROW(InstancedScene(s.device, s.package, InstancedOptions{.max_copies = (1u << 24) + 1}), std::invalid_argument);
}

TEST_F(Instanced, CompareExplicitAndVirtual) {
  Session& s = session();
  const std::vector<gpu::Camera> cameras{render::package_camera(s.package).to_gpu(128, 128)};
  const ExplicitVsVirtual c = compare_explicit_and_virtual(s.device, s.package, *s.virtual_scene, cameras, 3);
  std::printf("explicit vs virtual (128x128): %s\nvirtual scene: %s\n", c.to_json().dump(2).c_str(),
              render::to_json(s.virtual_scene->report()).dump().c_str());
  EXPECT_GE(c.agreement, 0.999);
  EXPECT_EQ(c.frames, 3u);
  EXPECT_GT(c.copies, 0u);
  EXPECT_GT(c.explicit_device_bytes, 0u);
  EXPECT_GT(c.virtual_device_bytes, 0u);
  EXPECT_GT(c.explicit_seconds_median, 0);
  EXPECT_GT(c.virtual_seconds_median, 0);
  EXPECT_THROW(compare_explicit_and_virtual(s.device, s.package, *s.virtual_scene, {}, 1), std::invalid_argument);
}

// A frame traced in parts of a few workgroups (as the viewer does between polls of its window) is
// the very frame render() makes, whatever the part sizes; a part never runs past the frame.
TEST_F(Instanced, FrameInPartsEqualsWholeFrame) {
  Session& s = session();
  render::Renderer renderer(s.device, *s.virtual_scene);
  const gpu::Camera camera = views(60, 0)[0];  // 60×60: strips and runs end inside workgroups
  const render::Frame whole = renderer.render(camera);
  for (const std::uint64_t budget : {std::uint64_t(1), std::uint64_t(100), std::uint64_t(600), std::uint64_t(1000000)}) {
    renderer.begin(camera);
    std::uint64_t traced = 0, parts = 0;
    for (bool complete = false; !complete; ++parts) {
      const render::Renderer::Part part = renderer.trace_part(budget);
      ASSERT_GT(part.pixels, 0u);
      traced += part.pixels;
      complete = part.complete;
    }
    EXPECT_THROW(renderer.trace_part(budget), std::logic_error);  // nothing left: the frame must be finished
    const render::Frame f = renderer.finish();
    EXPECT_EQ(traced, 60u * 60u) << "budget " << budget;
    if (budget == 1) {  // one workgroup of 8×8 at a time (60 = 7·8 + 4)
      EXPECT_EQ(parts, 8u * 8u);
    }
    ASSERT_EQ(f.hits.size(), whole.hits.size());
    EXPECT_EQ(0, std::memcmp(f.hits.data(), whole.hits.data(), whole.hits.size() * sizeof(gpu::PixelHit))) << "budget " << budget;
    EXPECT_EQ(f.rgba, whole.rgba) << "budget " << budget;
  }
  EXPECT_THROW(renderer.finish(), std::logic_error);
}

// Counting changes no pixel, and every pixel's counts obey the traversal's own laws: one µLAS query
// per primary ray, a prism entered only after its test, an nLAS query only for a molecule candidate
// that survived ownership, the drop list and the keep masks, a sphere test only for an atom candidate,
// and a hit only after a sphere test.
TEST_F(Instanced, CountersObeyTheTraversal) {
  Session& s = session();
  render::Renderer renderer(s.device, *s.virtual_scene);
  const gpu::Camera camera = views(48, 0)[0];
  const render::Frame plain = renderer.render(camera);
  renderer.set_settings(render::RenderSettings{.counters = true});
  const render::Frame counted = renderer.render(camera);
  ASSERT_EQ(counted.counters.size(), counted.hits.size() * gpu::NANO_RAY_COUNTER_COUNT);
  EXPECT_EQ(0, std::memcmp(plain.hits.data(), counted.hits.data(), plain.hits.size() * sizeof(gpu::PixelHit)));
  std::uint64_t membrane_pixels = 0;
  for (std::size_t p = 0; p < counted.hits.size(); ++p) {
    const std::uint32_t* c = &counted.counters[p * gpu::NANO_RAY_COUNTER_COUNT];
    ASSERT_EQ(c[gpu::NANO_RC_ULAS_QUERIES], 1u) << p;
    ASSERT_LE(c[gpu::NANO_RC_PRISMS_ENTERED], c[gpu::NANO_RC_PRISM_TESTS]) << p;
    ASSERT_LE(c[gpu::NANO_RC_PRISM_TESTS], c[gpu::NANO_RC_ULAS_CANDIDATES]) << p;
    ASSERT_LE(std::uint64_t(c[gpu::NANO_RC_NLAS_QUERIES]) + c[gpu::NANO_RC_OWNERSHIP_REJECTS] + c[gpu::NANO_RC_LISTED_REJECTS] +
                  c[gpu::NANO_RC_MASK_REJECTS],
              c[gpu::NANO_RC_MLAS_CANDIDATES]) << p;
    ASSERT_LE(c[gpu::NANO_RC_SPHERE_TESTS], c[gpu::NANO_RC_NLAS_CANDIDATES]) << p;
    if (counted.hits[p].atom != gpu::kNoHit) {
      ASSERT_GE(c[gpu::NANO_RC_SPHERE_TESTS], 1u) << p;
    }
    if (counted.hits[p].atom != gpu::kNoHit && counted.hits[p].kind == 0u) ++membrane_pixels;
  }
  EXPECT_GT(membrane_pixels, 0u);  // the view reaches the membrane, so the shell counters were exercised
}


// The level of detail: a threshold no copy reaches changes no pixel; one every copy reaches draws
// every copy as beads, which hold their atoms' spheres, so every pixel that showed an atom still
// shows something at most as far (and reports an atom of the same molecule type), and the beads
// really are coarser (some pixels change).
TEST_F(Instanced, BeadsHoldTheirAtoms) {
  Session& s = session();
  const gpu::Camera camera = views(64, 0)[0];
  render::Renderer renderer(s.device, *s.virtual_scene);
  const render::Frame atoms = renderer.render(camera);
  renderer.set_settings(render::RenderSettings{.lod_pixels = 1e-6});
  const render::Frame never = renderer.render(camera);
  EXPECT_EQ(0, std::memcmp(atoms.hits.data(), never.hits.data(), atoms.hits.size() * sizeof(gpu::PixelHit)));
  renderer.set_settings(render::RenderSettings{.lod_pixels = 1e4});
  const render::Frame beads = renderer.render(camera);
  const auto molecules = s.package.records<format::SectionKind::molecules>();
  const auto type_of = [&](std::uint32_t atom) {
    for (std::uint32_t t = 0; t < molecules.size(); ++t)
      if (atom >= molecules[t].first_atom && atom - molecules[t].first_atom < molecules[t].atom_count) return t;
    return ~0u;
  };
  std::uint64_t changed = 0;
  for (std::size_t p = 0; p < atoms.hits.size(); ++p) {
    const gpu::PixelHit& a = atoms.hits[p];
    const gpu::PixelHit& b = beads.hits[p];
    if (a.atom == gpu::kNoHit) continue;
    ASSERT_NE(b.atom, gpu::kNoHit) << p;
    ASSERT_LE(b.depth, a.depth * (1 + 1e-5f) + 1e-3f) << p;
    if (b.copy_number_lo == a.copy_number_lo && b.copy_number_hi == a.copy_number_hi) {
      EXPECT_EQ(type_of(b.atom), type_of(a.atom)) << p;
    }
    changed += b.atom != a.atom || b.depth != a.depth;
  }
  EXPECT_GT(changed, 0u);
}

// A package baked before format 2.5 has no beads: the renderer draws it at full detail and refuses
// a level of detail with a message naming the package, instead of drawing far copies as nothing.
TEST_F(Instanced, PackageWithoutBeadsRefusesLevelOfDetail) {
  Session& s = session();
  std::vector<format::SectionSource> sections;
  for (const format::SectionEntry& e : s.package.entries()) {
    const auto kind = static_cast<format::SectionKind>(e.kind);
    if (kind == format::SectionKind::beads || kind == format::SectionKind::bead_ranges) continue;
    // Draco-coded mesh sections are written back as their decoded records: the streams go too.
    if (kind == format::SectionKind::draco_meshes) continue;
    sections.push_back({e.kind, s.package.raw_bytes(kind), format::Compression::none, e.flags});
  }
  const std::vector<std::byte> bytes = format::build_package(sections);
  const format::Package old = format::Package::from_bytes(bytes, "old.nup");
  format::validate_semantics(old);
  render::GpuScene scene(s.device, old);
  EXPECT_FALSE(scene.has_beads());
  EXPECT_TRUE(s.virtual_scene->has_beads());
  render::Renderer renderer(s.device, scene);
  const render::Frame full = renderer.render(views(16, 0)[0]);
  EXPECT_GT(std::count_if(full.hits.begin(), full.hits.end(), [](const gpu::PixelHit& h) { return h.atom != gpu::kNoHit; }), 0);
  try {
    renderer.set_settings(render::RenderSettings{.lod_pixels = 1});
    ADD_FAILURE() << "a level of detail without beads was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "old.nup") << e.what();
    EXPECT_NE(e.rule().find("no beads"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nano::explicit_instancing

namespace nano::explicit_instancing {
namespace {

// The flat level (runtime/render/flat_level.hpp) puts the copies of the triangles in view into one
// TLAS and the µLAS skips those triangles: the picture must not change — the same atom of the same
// copy with the same ids at the same depth — whatever the budget lets in, and a budget must hold.
TEST_F(Instanced, FlatLevelShowsWhatTheVirtualPathShows) {
  Session& s = session();
  const std::vector<gpu::Camera> cameras = views(64, 4);
  render::Renderer virtual_renderer(s.device, *s.virtual_scene);  // flatten_bytes 0: every copy virtual
  std::vector<render::Frame> reference;
  for (const gpu::Camera& c : cameras) reference.push_back(virtual_renderer.render(c));
  ASSERT_EQ(s.virtual_scene->report().flattened_copies, 0u);

  for (const std::uint64_t budget : {std::uint64_t(64'000'000), std::uint64_t(1'500'000)}) {
    render::Renderer flat_renderer(s.device, *s.virtual_scene, render::RenderSettings{.flatten_bytes = budget});
    std::uint64_t flattened_views = 0;
    for (std::size_t i = 0; i < cameras.size(); ++i) {
      const render::Frame f = flat_renderer.render(cameras[i]);
      const render::LoadReport& r = s.virtual_scene->report();
      EXPECT_LE(r.memory.flat, budget);
      EXPECT_EQ(r.memory.flat == 0, r.flattened_copies == 0);
      flattened_views += r.flattened_copies > 0;
      const oracle::CompareResult a = oracle::compare_images(reference[i].hits, f.hits, 64, 64);
      std::printf("budget %llu B, view %zu: %llu copies of %llu triangles flat (%.2f MB); %llu/%llu agree (missed %llu, "
                  "other atom %llu, other ids %llu, depth %llu, max |Δt| %.3g Å)\n",
                  (unsigned long long)budget, i, (unsigned long long)r.flattened_copies,
                  (unsigned long long)r.flattened_triangles, r.memory.flat / 1e6, (unsigned long long)a.agree,
                  (unsigned long long)a.pixels, (unsigned long long)a.missed, (unsigned long long)a.different_atom,
                  (unsigned long long)a.different_ids, (unsigned long long)a.depth_only, a.max_depth_difference);
      EXPECT_EQ(a.missed, 0u) << "view " << i;
      EXPECT_EQ(a.different_ids, 0u) << "view " << i;
      EXPECT_GE(a.agreement(), 0.999) << "view " << i;
    }
    EXPECT_GE(flattened_views, 2u) << "budget " << budget << ": the level must really hold copies";
  }

  // Flattening off again restores the µLAS's prisms: the very frames of before, bit for bit.
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const render::Frame again = virtual_renderer.render(cameras[i]);
    EXPECT_EQ(s.virtual_scene->report().flattened_copies, 0u);
    EXPECT_EQ(0, std::memcmp(again.hits.data(), reference[i].hits.data(), again.hits.size() * sizeof(gpu::PixelHit)))
        << "view " << i;
  }
}

// A flat frame's counters: one flat query and one µLAS query per primary ray, an atom candidate of
// the flat level tested as a sphere; a budget too small for one triangle flattens nothing, and so
// do moved compartments (animation: the level holds the package's placement).
TEST_F(Instanced, FlatLevelCountsAndRefuses) {
  Session& s = session();
  const gpu::Camera camera = views(48, 0)[0];
  render::Renderer renderer(s.device, *s.virtual_scene, render::RenderSettings{.counters = true, .flatten_bytes = 64'000'000});
  const render::Frame f = renderer.render(camera);
  ASSERT_GT(s.virtual_scene->report().flattened_copies, 0u);
  std::uint64_t flat_candidates = 0;
  for (std::size_t p = 0; p < f.hits.size(); ++p) {
    const std::uint32_t* c = &f.counters[p * gpu::NANO_RAY_COUNTER_COUNT];
    ASSERT_EQ(c[gpu::NANO_RC_FLAT_QUERIES], 1u) << p;
    ASSERT_EQ(c[gpu::NANO_RC_ULAS_QUERIES], 1u) << p;
    ASSERT_LE(c[gpu::NANO_RC_SPHERE_TESTS], c[gpu::NANO_RC_NLAS_CANDIDATES] + c[gpu::NANO_RC_FLAT_CANDIDATES]) << p;
    flat_candidates += c[gpu::NANO_RC_FLAT_CANDIDATES];
  }
  EXPECT_GT(flat_candidates, 0u);

  renderer.set_settings(render::RenderSettings{.flatten_bytes = 1});
  renderer.render(camera);
  EXPECT_EQ(s.virtual_scene->report().flattened_copies, 0u);
  EXPECT_EQ(s.virtual_scene->report().memory.flat, 0u);

  std::vector<format::InstanceTransform> moved;
  for (const gpu::CompartmentInstance& ci : s.package.records<format::SectionKind::compartment_instances>())
    moved.push_back(format::instance_transform(ci));
  s.virtual_scene->set_flatten(64'000'000, camera, false);
  s.virtual_scene->set_eye(glm::dvec3(glm::vec3(camera.position)), moved);
  EXPECT_EQ(s.virtual_scene->report().flattened_copies, 0u);
  s.virtual_scene->set_flatten(0, camera, false);
}

// A bound on the copies enumerated per frame (the viewer's) grows the level over frames of one view
// to what an unbounded frame takes at once, and shows the same picture at every step.
TEST_F(Instanced, FlatLevelGrowsWithinItsEnumerationBound) {
  Session& s = session();
  const gpu::Camera camera = views(48, 0)[0];
  render::GpuScene fresh(s.device, s.package);  // nothing enumerated yet
  render::Renderer unbounded(s.device, *s.virtual_scene, render::RenderSettings{.flatten_bytes = 64'000'000});
  const render::Frame whole = unbounded.render(camera);
  const std::uint64_t all = s.virtual_scene->report().flattened_copies;
  render::Renderer bounded(s.device, fresh, render::RenderSettings{.flatten_bytes = 64'000'000, .flatten_new_copies = 500});
  std::uint64_t previous = 0, frames = 0;
  for (; frames < 100; ++frames) {
    const render::Frame f = bounded.render(camera);
    const std::uint64_t now = fresh.report().flattened_copies;
    const oracle::CompareResult a = oracle::compare_images(whole.hits, f.hits, 48, 48);
    EXPECT_EQ(a.missed + a.different_ids, 0u) << "frame " << frames;
    EXPECT_GE(now, previous);
    if (now == previous && frames > 0) break;
    if (frames == 0) {
      EXPECT_LT(now, all) << "the bound held back nothing";
    }
    previous = now;
  }
  EXPECT_EQ(previous, all);
  EXPECT_GT(frames, 1u);
}

}  // namespace
}  // namespace nano::explicit_instancing
