#include "bake/tiles/wang_sets.hpp"
#include "common/error.hpp"
#include "tests/tiles/tiles_test_support.hpp"

#include <gtest/gtest.h>

namespace nano::tiles {
namespace {

constexpr float kTileEdge = 120.f;
constexpr double kProteinPerUm2 = 0.5 / (kTileEdge * kTileEdge * 1e-8);  // one copy per two tiles

MembraneTileRequest membrane_request(uint64_t seed) {
  MembraneTileRequest r;
  r.types = {test::make_protein(), test::make_lipid()};
  r.edge = kTileEdge;
  r.molecules = {{0, kProteinPerUm2, 0.f}};
  r.lipids = LipidFill{1, 65.f, 16.f};
  r.seed = seed;
  return r;
}

// A periodic recipe repeated `times` along each lattice axis: explicit tiling across the wrap.
TilingRecipe repeated(const TilingRecipe& r, int times) {
  TilingRecipe big = r;
  for (int a = 0; a < r.dims; ++a) big.size[a] *= times;
  big.cells.resize(size_t(big.size[0]) * big.size[1] * big.size[2]);
  for (int k = 0; k < big.size[2]; ++k)
    for (int j = 0; j < big.size[1]; ++j)
      for (int i = 0; i < big.size[0]; ++i)
        big.cells[(size_t(k) * big.size[1] + j) * big.size[0] + i] = r.at(i % r.size[0], j % r.size[1], k % r.size[2]);
  return big;
}

class MembraneTilesSeeds : public testing::TestWithParam<uint64_t> {};

TEST_P(MembraneTilesSeeds, EveryRandomTilingIsCollisionFreeAtAtomLevel) {
  {
    const uint64_t seed = GetParam();
    const MembraneTileRequest req = membrane_request(seed);
    const WangSet set = make_membrane_tiles(req);
    ASSERT_EQ(set.tiles.size(), 16u);
    for (uint64_t recipe_seed : {seed, seed + 100}) {
      const TilingRecipe recipe = make_tiling_recipe(set.colouring, {6, 6, 1}, recipe_seed, false);
      const test::ExplicitTiling tiling = test::instantiate(set, recipe, req.types);
      EXPECT_TRUE(tiling.ownership_ok);
      EXPECT_GT(tiling.copies_per_type[0], 0u);
      EXPECT_GT(tiling.copies_per_type[1], 36u * 100);
      const test::ClosePair p = test::find_close_pair(tiling.atoms, 0.6f);
      EXPECT_FALSE(p.found) << "seed " << seed << ": atoms " << p.distance << " Å apart, limit " << p.limit;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, MembraneTilesSeeds, testing::Values(1u, 2u, 3u));

// A chart's in-plane stretch (eigenvalues 1.4 along 30° and 1.0 across, then 1.25 and 1.1 along
// 100°) applied to every copy centre of a 6×6 tiling: a set packed for e = 0.4 keeps the packer's
// full clearance; the same request packed rigidly (e = 0) does not — the case the bundled meshes hit.
TEST(MembraneTiles, PackedForTheChartStretchStaysCollisionFreeWhenStretched) {
  const auto stretch = [](float degrees, float major, float minor) {
    const float a = glm::radians(degrees);
    const glm::vec2 u(std::cos(a), std::sin(a)), v(-u.y, u.x);
    return [=](glm::vec3 p) {
      const glm::vec2 q = major * glm::dot(glm::vec2(p), u) * u + minor * glm::dot(glm::vec2(p), v) * v;
      return test::SurfacePlacement{glm::vec3(q, p.z)};
    };
  };
  MembraneTileRequest req = membrane_request(5);
  req.surface.lateral_stretch = 0.4f;
  const WangSet packed_for_stretch = make_membrane_tiles(req);
  req.surface.lateral_stretch = 0.f;
  const WangSet rigid = make_membrane_tiles(req);
  const TilingRecipe recipe = make_tiling_recipe(rigid.colouring, {6, 6, 1}, 5, false);
  int rigid_clashes = 0;
  for (const auto& place : {stretch(30.f, 1.4f, 1.f), stretch(100.f, 1.25f, 1.1f)}) {
    const test::ExplicitTiling ok = test::instantiate(packed_for_stretch, recipe, req.types, true, place);
    const test::ClosePair p = test::find_close_pair(ok.atoms, 0.99f);
    EXPECT_FALSE(p.found) << "atoms " << p.distance << " Å apart, limit " << p.limit;
    rigid_clashes += test::find_close_pair(test::instantiate(rigid, recipe, req.types, true, place).atoms, 0.99f).found;
  }
  EXPECT_GT(rigid_clashes, 0);
}

// Tile space rolled isometrically onto a cylinder of radius R (no chart stretch at all), the tile
// normal along the radius — outward (convex: what stands above spreads, what lies below squeezes)
// or inward (concave: the other way round) — and each copy turned with its local frame. A set packed
// for curvature 1/R keeps the packer's full clearance on both; the rigid set does not.
TEST(MembraneTiles, PackedForCurvatureStaysCollisionFreeOnCylinders) {
  constexpr float R = 150.f;
  const auto cylinder = [](float sign) {
    return [=](glm::vec3 p) {
      const float phi = sign * p.x / R;
      const glm::vec3 radial(std::sin(phi), 0.f, std::cos(phi));
      const glm::vec3 normal = sign * radial, ey(0.f, 1.f, 0.f);
      const glm::vec3 ex = glm::cross(ey, normal);
      return test::SurfacePlacement{(R + sign * p.z) * radial + p.y * ey, glm::mat3(ex, ey, normal)};
    };
  };
  MembraneTileRequest req = membrane_request(6);
  req.surface.curvature = 1.f / R;
  const WangSet packed_for_curvature = make_membrane_tiles(req);
  req.surface.curvature = 0.f;
  const WangSet rigid = make_membrane_tiles(req);
  // 4 × 3 tiles: 480 Å of arc, 3.2 rad, less than a turn, so the cylinder never meets itself.
  const TilingRecipe recipe = make_tiling_recipe(rigid.colouring, {4, 3, 1}, 6, false);
  int rigid_clashes = 0;
  for (const float sign : {1.f, -1.f}) {
    const test::ClosePair p =
        test::find_close_pair(test::instantiate(packed_for_curvature, recipe, req.types, true, cylinder(sign)).atoms, 0.99f);
    EXPECT_FALSE(p.found) << (sign > 0 ? "convex" : "concave") << ": atoms " << p.distance << " Å apart, limit " << p.limit;
    rigid_clashes += test::find_close_pair(test::instantiate(rigid, recipe, req.types, true, cylinder(sign)).atoms, 0.99f).found;
  }
  EXPECT_GT(rigid_clashes, 0);
}

// Facets: centres stay on a flat plane while each copy stands along a normal tilted about the y
// axis by α(x) = θ·sin(2πx/L), lifted along it, as copies on a flat triangle with interpolated
// normals do. Packed for tilt tan θ (and the normals' turn rate θ·2π/L), the set keeps the
// packer's full clearance; the rigid set does not.
TEST(MembraneTiles, PackedForNormalTiltStaysCollisionFreeOnAFacet) {
  constexpr float theta = 0.15f, L = 480.f;
  const auto facet = [](glm::vec3 p) {
    const float alpha = theta * std::sin(2.f * 3.14159265f * p.x / L);
    const glm::vec3 normal(std::sin(alpha), 0.f, std::cos(alpha)), ey(0.f, 1.f, 0.f);
    return test::SurfacePlacement{glm::vec3(p.x, p.y, 0.f) + p.z * normal, glm::mat3(glm::cross(ey, normal), ey, normal)};
  };
  MembraneTileRequest req = membrane_request(7);
  req.surface = {0.f, theta * 2.f * 3.14159265f / L, std::tan(theta), 1e9f};
  const WangSet packed_for_tilt = make_membrane_tiles(req);
  req.surface = {};
  const WangSet rigid = make_membrane_tiles(req);
  const TilingRecipe recipe = make_tiling_recipe(rigid.colouring, {4, 3, 1}, 7, false);
  const test::ClosePair p = test::find_close_pair(test::instantiate(packed_for_tilt, recipe, req.types, true, facet).atoms, 0.99f);
  EXPECT_FALSE(p.found) << "atoms " << p.distance << " Å apart, limit " << p.limit;
  EXPECT_TRUE(test::find_close_pair(test::instantiate(rigid, recipe, req.types, true, facet).atoms, 0.99f).found);
}

TEST(MembraneTiles, PeriodicRecipesAreCollisionFreeAcrossTheWrap) {
  const MembraneTileRequest req = membrane_request(4);
  const WangSet set = make_membrane_tiles(req);
  const TilingRecipe recipe = make_tiling_recipe(set.colouring, {3, 3, 1}, 4, true);
  const test::ExplicitTiling tiling = test::instantiate(set, repeated(recipe, 2), req.types);
  EXPECT_FALSE(test::find_close_pair(tiling.atoms, 0.6f).found);
}

// Densities counted in explicit tilings: proteins within 10% of the request; the report agrees
// with the count (lipids are best effort, so only the agreement is checked for them).
TEST(MembraneTiles, ExplicitDensityMatchesRequestAndReport) {
  for (uint64_t seed : {1u, 5u}) {
    const MembraneTileRequest req = membrane_request(seed);
    const WangSet set = make_membrane_tiles(req);
    const TilingRecipe recipe = make_tiling_recipe(set.colouring, {64, 64, 1}, seed, false);
    const test::ExplicitTiling tiling = test::instantiate(set, recipe, req.types, false);
    const double area_um2 = 64.0 * 64.0 * kTileEdge * kTileEdge * 1e-8;
    const double protein = tiling.copies_per_type[0] / area_um2, lipid = tiling.copies_per_type[1] / area_um2;
    EXPECT_NEAR(protein, kProteinPerUm2, 0.1 * kProteinPerUm2);
    ASSERT_EQ(set.densities.size(), 2u);
    for (const MoleculeDensity& d : set.densities) {
      const double counted = d.type == 0 ? protein : lipid;
      EXPECT_NEAR(d.achieved, counted, 0.05 * counted) << d.name;
    }
    EXPECT_EQ(set.densities[1].name, "lipid");
    EXPECT_DOUBLE_EQ(set.densities[1].requested, 2e8 / 65.0);
    // The lipid fill reaches a real membrane-like coverage, even if not the full 65 Å² per lipid.
    EXPECT_GT(lipid, 0.5 * 2e8 / 65.0);
  }
}

TEST(MembraneTiles, ProteinsStandAlongTheNormalAndLeafletsAreFlipped) {
  MembraneTileRequest req = membrane_request(6);
  req.types[0].up_axis = {1.f, 0.f, 0.f};  // this protein's "up" is its local x
  const WangSet set = make_membrane_tiles(req);
  int upper = 0, lower = 0;
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances) {
      const glm::vec3 up = test::rotate(in.rotation, req.types[in.type].up_axis);
      if (in.type == 0) {
        EXPECT_NEAR(up.z, 1.f, 1e-4f);
        EXPECT_FLOAT_EQ(in.position.z, 0.f);
      } else if (in.position.z > 0.f) {
        ++upper;
        EXPECT_NEAR(up.z, 1.f, 1e-4f);
        EXPECT_FLOAT_EQ(in.position.z, 16.f);
      } else {
        ++lower;
        EXPECT_NEAR(up.z, -1.f, 1e-4f);
        EXPECT_FLOAT_EQ(in.position.z, -16.f);
      }
    }
  EXPECT_GT(upper, 1000);
  EXPECT_NEAR(upper, lower, 0.1 * upper);
}

// The reported per-tile atom box is the true one (recomputed here), and the overhang is its excess.
TEST(MembraneTiles, TileAtomBoxesAndOverhang) {
  const MembraneTileRequest req = membrane_request(7);
  const WangSet set = make_membrane_tiles(req);
  float overhang = 0.f;
  for (const WangTile& t : set.tiles) {
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const Instance& in : t.instances)
      for (const AtomSphere& a : req.types[in.type].atoms) {
        const glm::vec3 c = in.position + test::rotate(in.rotation, a.centre);
        lo = glm::min(lo, c - a.radius);
        hi = glm::max(hi, c + a.radius);
      }
    EXPECT_NEAR(glm::length(lo - t.atoms_min), 0.f, 1e-3f);
    EXPECT_NEAR(glm::length(hi - t.atoms_max), 0.f, 1e-3f);
    overhang = std::max({overhang, -lo.x, -lo.y, hi.x - kTileEdge, hi.y - kTileEdge});
  }
  EXPECT_NEAR(set.max_overhang(), overhang, 1e-3f);
  EXPECT_GT(overhang, 0.f);  // copies do straddle tile edges
}

TEST(MembraneTiles, SameSeedSameBytesOtherSeedOtherTiles) {
  const WangSet a = make_membrane_tiles(membrane_request(9));
  const WangSet b = make_membrane_tiles(membrane_request(9));
  const WangSet c = make_membrane_tiles(membrane_request(10));
  EXPECT_EQ(test::set_bytes(a), test::set_bytes(b));
  EXPECT_NE(test::set_bytes(a), test::set_bytes(c));
}

// A periodic bilayer patch of lipid sticks, 5 x 5 per leaflet in a 39.5 Å box (62 Å² per lipid),
// spun and jittered so that a few neighbours clash and must be dropped from the tiled pattern.
LipidPatch stick_patch() {
  LipidPatch patch;
  patch.period_x = patch.period_y = 39.5f;
  test::TestRng rng{77};
  const glm::quat flip(0.f, 1.f, 0.f, 0.f);  // 180° about x: tails up, for the lower leaflet
  for (int leaflet = 0; leaflet < 2; ++leaflet)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const float angle = static_cast<float>(2.0 * M_PI * rng.next());
        const glm::quat spin(std::cos(angle / 2), 0.f, 0.f, std::sin(angle / 2));
        const glm::vec3 at(7.9f * i + 1.5f * float(rng.next()) + (leaflet ? 3.f : 0.f),
                           7.9f * j + 1.5f * float(rng.next()) - 50.f, leaflet ? -16.f : 16.f);
        patch.lipids.push_back({1, at, leaflet ? spin * flip : spin});
      }
  return patch;
}

// Patch lipids around proteins in explicit random tilings: no two lipid atoms closer than the
// patch clearance, no protein atom closer to anything than the generator's clearance (a lipid kept
// on one side of an edge against the other side's protein, or laid twice, would show), and the
// lipid density counted over a large tiling is the reported one and most of the patch's.
// The membrane request with the stick patch (clearance 0.85) in place of the lipid fill.
MembraneTileRequest patch_request() {
  MembraneTileRequest req = membrane_request(11);
  req.lipids.reset();
  req.lipid_patch = stick_patch();
  req.lipid_patch->clearance = 0.85f;
  return req;
}

TEST(MembraneTiles, LipidPatchIsCollisionFreeAndDense) {
  MembraneTileRequest req = patch_request();
  const WangSet set = make_membrane_tiles(req);
  for (uint64_t recipe_seed : {11u, 12u}) {
    const TilingRecipe recipe = make_tiling_recipe(set.colouring, {6, 6, 1}, recipe_seed, false);
    test::ExplicitTiling tiling = test::instantiate(set, recipe, req.types);
    EXPECT_TRUE(tiling.ownership_ok);
    EXPECT_GT(tiling.copies_per_type[0], 0u);
    const test::ClosePair all = test::find_close_pair(tiling.atoms, 0.849f);
    EXPECT_FALSE(all.found) << "atoms " << all.distance << " Å apart, limit " << all.limit;
    // Proteins among themselves keep the budget's clearance; a lipid packs against a protein at
    // the patch's own (checked above with every other pair).
    std::vector<test::WorldAtom> proteins;
    for (const test::WorldAtom& a : tiling.atoms)
      if (a.type != 1) proteins.push_back(a);
    const test::ClosePair protein = test::find_close_pair(proteins, 0.999f);
    EXPECT_FALSE(protein.found) << "atoms " << protein.distance << " Å apart, limit " << protein.limit;
  }
  const TilingRecipe recipe = make_tiling_recipe(set.colouring, {64, 64, 1}, 13, false);
  const test::ExplicitTiling counts = test::instantiate(set, recipe, req.types, false);
  const double lipids = counts.copies_per_type[1] / (64.0 * 64.0 * kTileEdge * kTileEdge * 1e-8);
  const double in_patch = 50.0 / (39.5 * 39.5 * 1e-8);
  ASSERT_EQ(set.densities.size(), 2u);
  EXPECT_EQ(set.densities[1].type, 1u);
  EXPECT_DOUBLE_EQ(set.densities[1].requested, in_patch);
  EXPECT_NEAR(set.densities[1].achieved, lipids, 0.03 * lipids);
  EXPECT_GT(lipids, 0.8 * in_patch);
  EXPECT_LT(lipids, in_patch);
  EXPECT_EQ(test::set_bytes(make_membrane_tiles(req)), test::set_bytes(set));
}

// The packer spreads the interiors, the layer's decisions and its refills over threads: the set is
// byte for byte the same on one, two and three, and still clash-free (the test above, on one).
TEST(MembraneTiles, SameSetWhateverTheThreads) {
  MembraneTileRequest req = patch_request();
  req.budget.threads = 1;
  const std::vector<std::uint8_t> one = test::set_bytes(make_membrane_tiles(req));
  for (const int threads : {2, 3}) {
    req.budget.threads = threads;
    const WangSet set = make_membrane_tiles(req);
    EXPECT_EQ(test::set_bytes(set), one) << threads << " threads";
    const test::ExplicitTiling tiling = test::instantiate(set, make_tiling_recipe(set.colouring, {4, 4, 1}, 5, false), req.types);
    EXPECT_FALSE(test::find_close_pair(tiling.atoms, 0.849f).found);
  }
}

// A protein whose lipids are displaced on the surface (kept per compartment, so copies may be
// dropped later) is laid through: lipids stay where they overlap it, and the lipid count is the
// patch's as if the protein were absent; without the flag no lipid touches a protein.
TEST(MembraneTiles, LipidsAreLaidThroughProteinsDisplacedOnTheSurface) {
  MembraneTileRequest req = patch_request();
  const WangSet refused = make_membrane_tiles(req);
  req.molecules[0].lipids_displaced_on_surface = true;
  const WangSet through = make_membrane_tiles(req);
  MembraneTileRequest no_protein = patch_request();
  no_protein.molecules.clear();
  const WangSet bare = make_membrane_tiles(no_protein);
  const auto lipid_protein_contact = [&](const WangSet& set) {
    const TilingRecipe recipe = make_tiling_recipe(set.colouring, {6, 6, 1}, 21, false);
    const test::ExplicitTiling tiling = test::instantiate(set, recipe, req.types);
    return test::find_close_pair(tiling.atoms, 0.849f).found;  // only lipid-protein pairs can come closer
  };
  EXPECT_FALSE(lipid_protein_contact(refused));
  EXPECT_TRUE(lipid_protein_contact(through)) << "no lipid was laid over a protein";
  const auto lipids = [](const WangSet& set) {
    for (const MoleculeDensity& d : set.densities)
      if (d.type == 1) return d.achieved;
    return 0.0;
  };
  EXPECT_DOUBLE_EQ(lipids(through), lipids(bare));
  EXPECT_LT(lipids(refused), lipids(through));
  EXPECT_EQ(through.densities[0].achieved, refused.densities[0].achieved) << "the proteins are packed alike";
}

// How far apart two copies of a tile stand sideways, between nearest images across its edges.
float sideways_apart(const Instance& a, const Instance& b) {
  glm::vec2 d = glm::vec2(a.position - b.position);
  for (int k = 0; k < 2; ++k) d[k] -= kTileEdge * std::round(d[k] / kTileEdge);
  return glm::length(d);
}

// Whether `alternate` is `lipid` put aside (bake/tiles/wang_sets.cpp): 1 Å sideways in the same
// pose, or half a turn about the tile normal in place (each axis of the pose with x and y reversed).
enum class Aside { no, shifted, turned };
Aside put_aside(const Instance& lipid, const Instance& alternate) {
  if (lipid.type != alternate.type || lipid.position.z != alternate.position.z) return Aside::no;
  const float apart = sideways_apart(lipid, alternate);
  if (std::abs(apart - 1.f) < 1e-3f && lipid.rotation == alternate.rotation) return Aside::shifted;
  const glm::mat3 a = glm::mat3_cast(lipid.rotation), b = glm::mat3_cast(alternate.rotation);
  bool half_turn = apart < 1e-3f;
  for (int k = 0; k < 3; ++k) half_turn = half_turn && glm::length(b[k] - glm::vec3(-a[k].x, -a[k].y, a[k].z)) < 1e-4f;
  return half_turn ? Aside::turned : Aside::no;
}

// Whether some lipid of the tile has `alternate` as its copy put aside.
bool put_aside_in(const WangTile& t, const Instance& alternate) {
  return std::any_of(t.instances.begin(), t.instances.end(),
                     [&](const Instance& o) { return &o != &alternate && put_aside(o, alternate) != Aside::no; });
}

// A membrane pruned on its whole surface (tiles packed rigid) keeps each layer lipid four ways 1 Å
// aside and turned half about the normal, as alternates of its type: a lipid the real surface pushes
// into a clash is shown there a hair away instead, where that fits (shell/membrane_pruning.hpp).
TEST(MembraneTiles, RigidLayerKeepsEachLipidAsideAndTurnedAsAlternates) {
  const MembraneTileRequest req = patch_request();
  ASSERT_TRUE(req.surface.rigid());
  const WangSet set = make_membrane_tiles(req);
  std::size_t lipids = 0, complete = 0;
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances) {
      if (in.alternate || in.type == 0) continue;
      ++lipids;
      int shifted = 0, turned = 0;
      for (const Instance& o : t.instances) {
        if (!o.alternate) continue;
        const Aside aside = put_aside(in, o);
        shifted += aside == Aside::shifted;
        turned += aside == Aside::turned;
      }
      EXPECT_LE(shifted, 4);
      EXPECT_LE(turned, 1);
      complete += shifted == 4 && turned == 1;
    }
  // A protein refuses some of them where they would cross it in the tile.
  EXPECT_GT(lipids, 0u);
  EXPECT_GT(complete, lipids * 9 / 10);
}

// A second species mixed into the patch's places (LipidSpecies): a thinner stick lipid (type 2)
// taking 40 % of the outer leaflet's places and 80 % of the inner one's. Random tilings stay
// clash-free at the patch clearance, the species sits only in its leaflets and never above its
// share, mixing opens no hole (as many lipids as the unmixed patch), and the set reports it.
MembraneTileRequest mixed_patch_request() {
  MembraneTileRequest req = patch_request();
  tiles::MoleculeType thin = test::make_lipid();
  thin.name = "thin";
  for (auto& a : thin.atoms) a.radius *= 0.8f;
  req.types.push_back(thin);
  LipidSpecies species;
  species.outer = 0.4f;
  species.inner = 0.8f;
  const glm::quat flip(0.f, 1.f, 0.f, 0.f);
  species.conformers = {{2, glm::vec3(0, 0, 16.f), glm::quat(1, 0, 0, 0)}, {2, glm::vec3(0, 0, -16.f), flip}};
  req.lipid_patch->mix = {species};
  return req;
}

// The places a mixed species may take are ranked several at a time on the jobs: the same set.
TEST(MembraneTiles, SameMixedSetWhateverTheThreads) {
  MembraneTileRequest req = mixed_patch_request();
  req.budget.threads = 1;
  const std::vector<std::uint8_t> one = test::set_bytes(make_membrane_tiles(req));
  req.budget.threads = 3;
  EXPECT_EQ(test::set_bytes(make_membrane_tiles(req)), one);
}

TEST(MembraneTiles, LipidMixTakesPlacesWithoutOpeningHoles) {
  const WangSet unmixed = make_membrane_tiles(patch_request());
  MembraneTileRequest req = mixed_patch_request();
  const WangSet set = make_membrane_tiles(req);
  for (uint64_t recipe_seed : {11u, 12u}) {
    const TilingRecipe recipe = make_tiling_recipe(set.colouring, {6, 6, 1}, recipe_seed, false);
    test::ExplicitTiling tiling = test::instantiate(set, recipe, req.types);
    const test::ClosePair all = test::find_close_pair(tiling.atoms, 0.849f);
    EXPECT_FALSE(all.found) << "atoms " << all.distance << " Å apart, limit " << all.limit;
  }
  std::size_t outer[3] = {}, inner[3] = {};
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances)
      if (!in.alternate) ++(in.position.z >= 0.f ? outer : inner)[in.type];
  // Every place given to the thin species keeps its base lipid as an alternate, at the place (the
  // conformer may stand a nudge away) in the same leaflet, unless a protein refuses it there. The
  // other alternates stand in for layer lipids a protein refused (shown where the pruning drops
  // that protein): each within reach of a protein of the set, in the tile or across its edge.
  const auto reach = [&](uint32_t type) {
    float r = 0.f;
    for (const auto& a : req.types.at(type).atoms) r = std::max(r, glm::length(a.centre) + a.radius);
    return r;
  };
  std::vector<glm::vec3> proteins;
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances)
      if (in.type == 0 && !in.alternate) proteins.push_back(in.position);
  const auto under_a_protein = [&](const Instance& in) {
    return std::any_of(proteins.begin(), proteins.end(), [&](const glm::vec3& p) {
      glm::vec2 d = glm::vec2(p - in.position);
      for (int k = 0; k < 2; ++k) d[k] -= kTileEdge * std::round(d[k] / kTileEdge);  // the nearest image
      return glm::length(d) < reach(0) + reach(in.type);
    });
  };
  std::size_t alternates = 0, backed = 0, stand_ins = 0, asides = 0;
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances) {
      if (!in.alternate) {
        backed += in.has_alternate;
        EXPECT_EQ(in.has_alternate, in.type == 2u);
        continue;
      }
      if (put_aside_in(t, in)) {  // a lipid a hair aside or turned
        ++asides;
        continue;
      }
      const bool beside = in.type == 1u && std::any_of(t.instances.begin(), t.instances.end(), [&](const Instance& o) {
        return o.has_alternate && (o.position.z >= 0.f) == (in.position.z >= 0.f) &&
               glm::length(glm::vec2(o.position - in.position)) < 1.2f;
      });
      if (beside) {
        ++alternates;
        continue;
      }
      ++stand_ins;
      EXPECT_TRUE(under_a_protein(in)) << "an alternate neither beside a mixed lipid nor where a protein stands";
    }
  EXPECT_GT(stand_ins, 0u);
  EXPECT_GT(asides, 0u);
  EXPECT_LE(alternates, backed);
  EXPECT_GT(alternates, backed / 2);
  EXPECT_GT(outer[2], 0u);
  EXPECT_GT(inner[2], outer[2]);
  EXPECT_LE(double(outer[2]), 0.45 * double(outer[1] + outer[2]));
  EXPECT_LE(double(inner[2]), 0.85 * double(inner[1] + inner[2]));
  std::size_t lipids_mixed = 0, lipids_unmixed = 0;
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances) lipids_mixed += in.type != 0 && !in.alternate;
  for (const WangTile& t : unmixed.tiles)
    for (const Instance& in : t.instances) lipids_unmixed += in.type != 0 && !in.alternate;
  EXPECT_GE(double(lipids_mixed), 0.97 * double(lipids_unmixed));
  const auto reported = std::find_if(set.densities.begin(), set.densities.end(), [](const MoleculeDensity& d) { return d.name == "thin"; });
  ASSERT_NE(reported, set.densities.end());
  EXPECT_GT(reported->achieved, 0.0);
  EXPECT_GT(reported->requested, reported->achieved * 0.9);
  req.lipid_patch->mix[0].inner = 1.1f;  // more than the whole inner leaflet
  EXPECT_THROW(make_membrane_tiles(req), InputError);
}

// Where a protein refuses a patch lipid, the hole is refilled with a conformer of the refused
// lipid's own kind: a small kind (one atom, in one of the 25 places of each leaflet) that would fit
// in any stick's hole never takes a stick's place, so the set holds no more of it than the patch
// laid without proteins (drawn from the whole leaflet it filled the sticks' holes: the sterol of the
// virion's envelope went from 4.5 % to 11 % of a leaflet beside its M dimers).
TEST(MembraneTiles, AHoleIsRefilledWithItsOwnKind) {
  const auto with_dots = [](MembraneTileRequest req) {
    req.types.push_back(MoleculeType{"dot", {{{0.f, 0.f, 0.f}, 1.5f}}, 0.f, {0.f, 0.f, 1.f}});
    for (const std::size_t place : {std::size_t{12}, std::size_t{37}}) req.lipid_patch->lipids.at(place).type = 2;
    return req;
  };
  const auto kept = [](const WangSet& set, uint32_t type) {
    std::size_t n = 0;
    for (const WangTile& t : set.tiles)
      for (const Instance& in : t.instances) n += in.type == type && !in.alternate;
    return n;
  };
  MembraneTileRequest bare = with_dots(patch_request());
  bare.molecules.clear();
  const WangSet without_proteins = make_membrane_tiles(bare);
  MembraneTileRequest req = with_dots(patch_request());
  req.molecules[0].copies_per_um2 *= 8.0;  // four proteins a tile: many sticks refused
  const WangSet set = make_membrane_tiles(req);
  ASSERT_GT(kept(set, 0), 0u);
  ASSERT_GT(kept(without_proteins, 2), 0u);
  EXPECT_LE(kept(set, 2), kept(without_proteins, 2));
  EXPECT_LT(kept(set, 1), kept(without_proteins, 1)) << "the proteins refused no stick";
}

TEST(MembraneTiles, ImpossibleRequestsThrowInputError) {
  MembraneTileRequest dense = membrane_request(1);
  dense.lipids.reset();
  dense.molecules[0].copies_per_um2 = 1e8 / (30.0 * 30.0);  // one 50 Å protein per 900 Å²
  try {
    make_membrane_tiles(dense);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "protein");
    EXPECT_NE(e.rule().find("best achieved"), std::string::npos) << e.what();
  }
  MembraneTileRequest wide = membrane_request(1);
  wide.edge = 40.f;  // narrower than the protein
  EXPECT_THROW(make_membrane_tiles(wide), InputError);
  MembraneTileRequest bad = membrane_request(1);
  bad.molecules[0].type = 7;
  EXPECT_THROW(make_membrane_tiles(bad), InputError);
  bad = membrane_request(1);
  bad.molecules[0].copies_per_um2 = -1.0;
  EXPECT_THROW(make_membrane_tiles(bad), InputError);
  bad = membrane_request(1);
  bad.lipid_patch = stick_patch();  // together with the lipid fill
  EXPECT_THROW(make_membrane_tiles(bad), InputError);
  bad.lipids.reset();
  bad.lipid_patch->period_y = 0.f;
  EXPECT_THROW(make_membrane_tiles(bad), InputError);
  for (float e : {-0.1f, NAN, INFINITY}) {
    for (float tiles::SurfaceDistortion::*member : {&tiles::SurfaceDistortion::lateral_stretch,
                                                    &tiles::SurfaceDistortion::curvature, &tiles::SurfaceDistortion::tilt}) {
      bad = membrane_request(1);
      bad.surface.*member = e;
      EXPECT_THROW(make_membrane_tiles(bad), InputError) << e;
    }
  }
}

}  // namespace
}  // namespace nano::tiles

namespace nano::tiles {
namespace {

// A protein so sparse that the whole set holds about one copy: 1.17 copies wanted in 16 tiles.
// Every copy counts per tile as its unit occurs: 1/16 in a tile's interior, 1/2 on an edge of two
// colours, 1 in the corner every tile shares. The set must come as close to the request as whole
// copies allow (one copy, 0.85x), never by a shared copy that overshoots many times over.
TEST(MembraneTiles, ASparseProteinIsPlacedAsCloseAsWholeCopiesAllow) {
  for (uint64_t seed : {1u, 2u, 3u, 4u}) {
    MembraneTileRequest r = membrane_request(seed);
    const double set_um2 = 16 * kTileEdge * kTileEdge * 1e-8;
    r.molecules = {{0, 1.17 / set_um2, 0.f}};
    r.lipids.reset();
    const WangSet set = make_membrane_tiles(r);
    ASSERT_EQ(set.densities.size(), 1u);
    const double copies_in_set = set.densities[0].achieved * set_um2;
    EXPECT_NEAR(copies_in_set, 1.17, 0.5) << "seed " << seed << ": " << set.densities[0].achieved << " per µm² of "
                                          << set.densities[0].requested;
  }
}

}  // namespace
}  // namespace nano::tiles
