// What lies under a roof is the building (roof_cover.h): constructed objects with known
// classes and kinds through claimPointsUnderRoofs().
#include <pcl_ls3d/segmentation/roof_cover.h>

#include <gtest/gtest.h>

#include <limits>
#include <vector>

using pcl_ls3d::segmentation::claimPointsUnderRoofs;
using pcl_ls3d::segmentation::ObjectClass;
using pcl_ls3d::segmentation::SegmentKind;

namespace {

constexpr float kStep = 0.25f;  // point spacing, also the cell and the clearance

/// Points with their object and the kind of their segment.
struct Scene
{
  std::vector<Eigen::Vector3f> points;
  std::vector<int> labels;
  std::vector<SegmentKind> kinds;

  std::size_t
  add(float x, float y, float z, int label, SegmentKind kind)
  {
    points.emplace_back(x, y, z);
    labels.push_back(label);
    kinds.push_back(kind);
    return points.size() - 1;
  }

  /// A horizontal grid x0..x1 × y0..y1 at height z.
  void
  roof(float x0, float x1, float y0, float y1, float z, int label)
  {
    for (float x = x0; x < x1; x += kStep)
      for (float y = y0; y < y1; y += kStep)
        add(x, y, z, label, SegmentKind::Solid);
  }

  /// A vertical sheet at x, y0..y1, z0..z1 (facade scatter, crown sides: rough).
  std::vector<std::size_t>
  sheet(float x, float y0, float y1, float z0, float z1, int label)
  {
    std::vector<std::size_t> added;
    for (float y = y0; y < y1; y += kStep)
      for (float z = z0; z < z1; z += kStep)
        added.push_back(add(x, y, z, label, SegmentKind::Rough));
    return added;
  }
};

enum Object
{
  kHouse,
  kShed,
  kTreeGroup,
  kCrownOverRoof,
  kCarUnderCarport,
  kObjects
};

std::vector<ObjectClass>
classesOfTheScene()
{
  std::vector<ObjectClass> c(kObjects);
  c[kHouse] = c[kShed] = ObjectClass::Building;
  c[kTreeGroup] = c[kCrownOverRoof] = ObjectClass::Vegetation;
  c[kCarUnderCarport] = ObjectClass::Car;
  return c;
}

}  // namespace

TEST(RoofCover, FacadeInATreeGroupJoinsTheBuildingAboveIt)
{
  Scene s;
  s.roof(0.f, 10.f, 0.f, 10.f, 6.f, kHouse);  // flat roof, eaves at x = 10
  s.roof(20.f, 26.f, 0.f, 6.f, 3.f, kShed);   // a lower building farther east
  // The tree group holds the house's facade under its eaves (x = 9.9), the shed's (x = 25.9)
  // and its own crowns in front of both (x ≥ 10.5, outside every roof).
  const auto house_wall = s.sheet(9.9f, 2.f, 8.f, 1.f, 5.f, kTreeGroup);
  const auto shed_wall = s.sheet(25.9f, 1.f, 5.f, 0.5f, 2.5f, kTreeGroup);
  const auto crowns = s.sheet(10.6f, 0.f, 10.f, 2.f, 8.f, kTreeGroup);
  // A crown resting on the roof (above it), a car under a carport-like overhang (not vegetation),
  // and a point with no coordinates.
  std::vector<std::size_t> over_roof;
  for (float x = 3.f; x < 5.f; x += kStep)
    over_roof.push_back(s.add(x, 4.f, 6.2f + 0.5f * (x - 3.f), kCrownOverRoof, SegmentKind::Rough));
  const auto car = s.sheet(2.f, 1.f, 3.f, 0.3f, 1.5f, kCarUnderCarport);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::size_t lost = s.add(nan, nan, nan, kTreeGroup, SegmentKind::Rough);
  std::vector<int> labels = s.labels;

  const std::size_t moved =
      claimPointsUnderRoofs(s.points, s.kinds, classesOfTheScene(), kStep, kStep, labels);

  EXPECT_EQ(moved, house_wall.size() + shed_wall.size());
  for (const auto p : house_wall)
    ASSERT_EQ(labels[p], kHouse) << "facade point " << s.points[p].transpose();
  for (const auto p : shed_wall)
    ASSERT_EQ(labels[p], kShed) << "facade point " << s.points[p].transpose();
  for (const auto p : crowns)
    ASSERT_EQ(labels[p], kTreeGroup) << "crown point in front of the facade";
  for (const auto p : over_roof)
    ASSERT_EQ(labels[p], kCrownOverRoof) << "crown point above the roof";
  for (const auto p : car)
    ASSERT_EQ(labels[p], kCarUnderCarport) << "a car is no vegetation";
  EXPECT_EQ(labels[lost], kTreeGroup);
}

TEST(RoofCover, RoofCellsAreTheBuildingsSolidSegmentsOnly)
{
  Scene s;
  // A building whose only points here are a rough facade 4-6 m up (no roof plane), and a
  // vegetation object's flat solid-looking top: neither gives roof cells, so the shrubs below
  // both stay.
  s.sheet(0.f, 0.f, 5.f, 4.f, 6.f, kHouse);
  s.roof(-2.f, -0.5f, 0.f, 5.f, 6.f, kTreeGroup);
  for (float y = 0.f; y < 5.f; y += kStep) {
    s.add(0.f, y, 1.f, kCrownOverRoof, SegmentKind::Rough);   // under the facade
    s.add(-1.f, y, 1.f, kCrownOverRoof, SegmentKind::Rough);  // under the hedge top
  }
  s.add(1.f, 1.f, 1.f, -1, SegmentKind::Rough);  // in no object
  std::vector<int> labels = s.labels;

  EXPECT_EQ(claimPointsUnderRoofs(s.points, s.kinds, classesOfTheScene(), kStep, kStep, labels), 0u);
  EXPECT_EQ(labels, s.labels);
}

TEST(RoofCover, MismatchedSizesMoveNothing)
{
  Scene s;
  s.roof(0.f, 2.f, 0.f, 2.f, 6.f, kHouse);
  s.sheet(1.f, 0.f, 2.f, 1.f, 3.f, kTreeGroup);
  std::vector<int> labels = s.labels;
  std::vector<SegmentKind> short_kinds(s.kinds.begin(), s.kinds.end() - 1);
  EXPECT_EQ(claimPointsUnderRoofs(s.points, short_kinds, classesOfTheScene(), kStep, kStep, labels), 0u);
  EXPECT_EQ(claimPointsUnderRoofs(s.points, s.kinds, classesOfTheScene(), 0.0, kStep, labels), 0u);
  EXPECT_EQ(labels, s.labels);
}
