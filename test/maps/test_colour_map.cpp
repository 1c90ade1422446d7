// Colour maps (maps/colour_map.h): ends clamp, steps jump, the lasoverlap-style classes put
// |d| below 0.10 near white and beyond 0.20 in saturated blue / red, viridis runs dark to light.
#include <pcl_ls3d/maps/colour_map.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d::maps;

namespace {
int
lightness(Rgb c)
{
  return c.r + c.g + c.b;
}
}  // namespace

TEST(ColourMap, InterpolatesBetweenStopsAndClampsOutside)
{
  const ColourMap m(std::vector<ColourMap::Stop>{{0.0, {0, 0, 0}}, {1.0, {200, 100, 50}}});
  ASSERT_TRUE(m.valid());
  EXPECT_EQ(m.colour(0.5), (Rgb{100, 50, 25}));
  EXPECT_EQ(m.colour(-5.0), (Rgb{0, 0, 0}));
  EXPECT_EQ(m.colour(7.0), (Rgb{200, 100, 50}));
  EXPECT_EQ(m.colour(NAN), (Rgb{0, 0, 0}));
  using Stops = std::vector<ColourMap::Stop>;
  EXPECT_FALSE(ColourMap(Stops{{1.0, {}}, {0.0, {}}}).valid());
  EXPECT_FALSE(ColourMap(Stops{{0.0, {}}}).valid());
}

TEST(ColourMap, TwoStopsAtOneValueMakeAStep)
{
  const ColourMap m(std::vector<ColourMap::Stop>{
      {0.0, {0, 0, 0}}, {1.0, {0, 0, 0}}, {1.0, {255, 255, 255}}, {2.0, {255, 255, 255}}});
  EXPECT_EQ(m.colour(0.999), (Rgb{0, 0, 0}));
  EXPECT_EQ(m.colour(1.0), (Rgb{255, 255, 255}));
  ASSERT_EQ(m.steps().size(), 1u);
  EXPECT_DOUBLE_EQ(m.steps()[0], 1.0);
}

TEST(ColourMap, BandedDivergingShowsTheToleranceClasses)
{
  const ColourMap m = ColourMap::bandedDiverging(0.10, 0.20);
  EXPECT_DOUBLE_EQ(m.min(), -0.30);
  EXPECT_DOUBLE_EQ(m.max(), 0.30);
  EXPECT_EQ(m.steps().size(), 4u);  // ±0.10, ±0.20
  // Inside the tolerance: light; beyond: dark; negative blue, positive red.
  EXPECT_GT(lightness(m.colour(0.0)), 700);
  EXPECT_GT(lightness(m.colour(0.09)), 550);
  EXPECT_GT(lightness(m.colour(-0.09)), 550);
  EXPECT_LT(lightness(m.colour(0.25)), 400);
  EXPECT_LT(lightness(m.colour(-0.25)), 400);
  EXPECT_GT(m.colour(0.25).r, m.colour(0.25).b);
  EXPECT_GT(m.colour(-0.25).b, m.colour(-0.25).r);
  // The classes differ visibly across each boundary.
  for (double edge : {-0.2, -0.1, 0.1, 0.2})
    EXPECT_GT(std::abs(lightness(m.colour(edge - 1e-6)) - lightness(m.colour(edge + 1e-6))), 60)
        << "edge " << edge;
  EXPECT_EQ(m.ticks().size(), 7u);
}

TEST(ColourMap, SequentialAndDivergingRamps)
{
  const ColourMap v = ColourMap::sequential(0.0, 10.0);
  EXPECT_LT(lightness(v.colour(0.0)), lightness(v.colour(10.0)));
  EXPECT_EQ(v.colour(0.0), Rgb::hex(0x440154));
  EXPECT_EQ(v.colour(10.0), Rgb::hex(0xfde725));
  const ColourMap d = ColourMap::diverging(1.0);
  EXPECT_EQ(d.colour(0.0), Rgb::hex(0xf7f7f7));
  EXPECT_EQ(d.colour(-1.0), Rgb::hex(0x053061));
  EXPECT_EQ(d.colour(1.0), Rgb::hex(0x67001f));
  EXPECT_TRUE(d.steps().empty());
}
