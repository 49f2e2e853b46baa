// The tile-set stage's cache: a set survives its bytes and its file, hostile bytes are refused with a
// reason, the key follows every input the set depends on but the thread count, and a second
// request for the same set is served from the cache with the same set.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bake/scene_bake/tile_set_cache.hpp"
#include "bake/tiles/wang_sets.hpp"
#include "tests/tiles/tiles_test_support.hpp"

namespace nano::scene_bake {
namespace {

tiles::SolubleCubeRequest small_request() {
  tiles::SolubleCubeRequest r;
  r.types = {tiles::test::make_haemoglobin()};
  r.edge = 150.f;
  r.molecules = {{0, tiles::copies_per_um3_from_millimolar(2.0)}};
  r.seed = 3;
  return r;
}

TEST(TileSetCache, ASetSurvivesItsBytes) {
  const tiles::WangSet set = tiles::make_soluble_cubes(small_request());
  std::string why;
  const std::optional<tiles::WangSet> back = decode_wang_set(encode_wang_set(set), 1, why);
  ASSERT_TRUE(back) << why;
  EXPECT_EQ(encode_wang_set(*back), encode_wang_set(set));
  ASSERT_EQ(back->tiles.size(), set.tiles.size());
  EXPECT_EQ(back->densities.size(), set.densities.size());
}

TEST(TileSetCache, HostileBytesAreRefusedWithAReason) {
  const std::vector<std::byte> bytes = encode_wang_set(tiles::make_soluble_cubes(small_request()));
  std::string why;
  for (std::size_t cut : {std::size_t{0}, std::size_t{7}, bytes.size() / 2, bytes.size() - 1}) {
    EXPECT_FALSE(decode_wang_set(std::span(bytes).first(cut), 1, why)) << cut;
    EXPECT_FALSE(why.empty());
  }
  EXPECT_FALSE(decode_wang_set(bytes, 0, why)) << "a copy of type 0 in a set of no types";
  // A side colour beyond the set's colours (the recipe would index past its tiles): the first tile's
  // colours follow dims, edge, colouring dims, colours, variants and the tile count (4+4+4+4+4+8 bytes).
  std::vector<std::byte> bad_colour = bytes;
  bad_colour[28] = std::byte{200};
  EXPECT_FALSE(decode_wang_set(bad_colour, 1, why));
  EXPECT_NE(why.find("colour"), std::string::npos) << why;
}

TEST(TileSetCache, TheKeyFollowsTheInputsButNotTheThreads) {
  const tiles::SolubleCubeRequest base = small_request();
  tiles::SolubleCubeRequest threads = base, seed = base, density = base, atom = base;
  threads.budget.threads = 7;
  seed.seed += 1;
  density.molecules[0].copies_per_um3 *= 1.01;
  atom.types[0].atoms[0].radius += 0.01f;
  EXPECT_EQ(tile_set_key(threads).hex(), tile_set_key(base).hex());
  for (const auto* other : {&seed, &density, &atom}) EXPECT_NE(tile_set_key(*other).hex(), tile_set_key(base).hex());
}

TEST(TileSetCache, TheSecondRequestIsServedFromTheCache) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "tile_set_cache_test";
  std::filesystem::remove_all(dir);
  const tiles::SolubleCubeRequest request = small_request();
  bool from_cache = true;
  const tiles::WangSet made = cached_soluble_cubes(request, dir, from_cache);
  EXPECT_FALSE(from_cache);
  const tiles::WangSet read = cached_soluble_cubes(request, dir, from_cache);
  EXPECT_TRUE(from_cache);
  EXPECT_EQ(encode_wang_set(read), encode_wang_set(made));
  {  // a damaged file is refused (with a warning) and the set packed again
    std::ofstream garbage(tile_set_cache_file(dir, tile_set_key(request)), std::ios::binary | std::ios::trunc);
    garbage << "not a tile set";
  }
  EXPECT_FALSE(load_wang_set(dir, tile_set_key(request), 1));
  const tiles::WangSet again = cached_soluble_cubes(request, dir, from_cache);
  EXPECT_FALSE(from_cache);
  EXPECT_EQ(encode_wang_set(again), encode_wang_set(made));
  EXPECT_FALSE(cached_soluble_cubes(request, std::nullopt, from_cache).tiles.empty());
  EXPECT_FALSE(from_cache);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nano::scene_bake
