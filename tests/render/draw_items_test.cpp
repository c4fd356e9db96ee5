// The sort key of render/draw_items.h: opaque draws by program, then material,
// then front to back; blended ones back to front; ties keep their order.
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include "render/draw_items.h"

using namespace engine;

TEST(DrawItems, OpaqueKeysOrderByProgramThenMaterialThenDistance) {
  // 20 000 random pairs: the key's order must be the lexicographic one.
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::uint32_t> program(0, 40), material(0, 300);
  std::uniform_real_distribution<double> distance(0.0, 5.0e4);
  for (int i = 0; i < 20000; ++i) {
    const std::uint32_t pa = program(rng), pb = program(rng), ma = material(rng), mb = material(rng);
    const double da = distance(rng), db = i % 7 ? distance(rng) : da;
    // The key holds distances as floats: compare what it holds.
    const float fa = float(da), fb = float(db);
    const std::uint64_t ka = opaqueKey(pa, ma, da), kb = opaqueKey(pb, mb, db);
    EXPECT_EQ(ka < kb, std::tie(pa, ma, fa) < std::tie(pb, mb, fb)) << pa << " " << ma << " " << da;
    EXPECT_EQ(ka == kb, pa == pb && ma == mb && fa == fb);
  }
}

TEST(DrawItems, BlendKeysPutTheFarthestFirst) {
  std::vector<DrawItem> items;
  for (double d : {0.5, 30.0, 2.0, 1.0e4, 0.0, 7.25}) items.push_back({DrawItem::Source::Character, 0, 0, 0, 0, blendKey(d)});
  sortDrawItems(items);
  std::vector<std::uint64_t> want;
  for (double d : {1.0e4, 30.0, 7.25, 2.0, 0.5, 0.0}) want.push_back(blendKey(d));
  for (size_t i = 0; i < items.size(); ++i) EXPECT_EQ(items[i].key, want[i]) << i;
}

// Unbounded shapes (planes) stand at distance 0, and a negative distance cannot
// wrap to the far end of the key.
TEST(DrawItems, EqualKeysKeepTheirOrderAndNegativeDistancesClamp) {
  EXPECT_EQ(opaqueKey(3, 4, -1.0), opaqueKey(3, 4, 0.0));
  EXPECT_EQ(blendKey(-2.0), blendKey(0.0));
  std::vector<DrawItem> items;
  for (int i = 0; i < 50; ++i) items.push_back({DrawItem::Source::Shape, i, -1, -1, 7, opaqueKey(7, 2, 0.0)});
  items.push_back({DrawItem::Source::Shape, 99, -1, -1, 1, opaqueKey(1, 9, 3.0)});
  sortDrawItems(items);
  EXPECT_EQ(items[0].object, 99);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(items[size_t(i) + 1].object, i);
}
