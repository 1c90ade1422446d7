// Object classes of IMRG's object level (object_classes.h): constructed objects of known class
// through classifyObjects(), and IMRG on a generated scene scored point by point against the
// generator's labels (seed 4: the thresholds were looked at on seeds 1-3 and the IGN tuning
// tiles only).
#include "io/tool_run.h"

#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/segmentation/multi_rule_region_growing.h>
#include <pcl_ls3d/segmentation/object_classes.h>
#include <pcl_ls3d/synth/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>

using pcl_ls3d::segmentation::classifyObjects;
using pcl_ls3d::segmentation::ObjectClass;
using pcl_ls3d::segmentation::ObjectClassSettings;
using pcl_ls3d::segmentation::SegmentKind;

namespace {

/// Points, object labels, kinds and ground flags, built object by object.
struct Scene
{
  std::vector<Eigen::Vector3f> points;
  std::vector<int> labels;
  std::vector<SegmentKind> kinds;
  std::vector<char> ground;

  void
  add(float x, float y, float z, int label, SegmentKind kind, bool on_ground = false)
  {
    points.emplace_back(x, y, z);
    labels.push_back(label);
    kinds.push_back(kind);
    ground.push_back(on_ground ? 1 : 0);
  }
  /// A horizontal rectangle sampled every `step`.
  void
  rectangle(float x0, float x1, float y0, float y1, float z, float step, int label, SegmentKind kind,
            bool on_ground = false)
  {
    for (float x = x0; x <= x1; x += step)
      for (float y = y0; y <= y1; y += step)
        add(x, y, z, label, kind, on_ground);
  }
  std::vector<ObjectClass>
  classify() const
  {
    return classifyObjects(points, labels, kinds, ground, ObjectClassSettings{});
  }
};

/// Terrain (object 0) from −40 to 40 m at z 0, with holes (x0, x1, y0, y1) where objects stand
/// on no ground point, so that their terrain comes from the margin around them.
void
addTerrain(Scene& s, const std::vector<std::array<float, 4>>& holes = {})
{
  for (float x = -40.0f; x <= 40.0f; x += 0.5f)
    for (float y = -40.0f; y <= 40.0f; y += 0.5f) {
      const bool under = std::any_of(holes.begin(), holes.end(), [&](const auto& h) {
        return x >= h[0] && x <= h[1] && y >= h[2] && y <= h[3];
      });
      if (!under)
        s.add(x, y, 0.0f, 0, SegmentKind::Ground, true);
    }
}

/// A flat layer of rough points, 0.2 m apart, jittered 0.15 m: a car's roof, a shrub's top.
void
addRoughBox(Scene& s, std::mt19937& rng, const Eigen::Vector3f& corner, float length, float width, int label)
{
  std::uniform_real_distribution<float> jitter(-0.15f, 0.15f);
  for (float x = corner.x(); x <= corner.x() + length; x += 0.2f)
    for (float y = corner.y(); y <= corner.y() + width; y += 0.2f)
      s.add(x + jitter(rng), y + jitter(rng), corner.z() + jitter(rng), label, SegmentKind::Rough);
}

}  // namespace

// Each object is what its geometry says: a roof 6 m up is a building, a 4.5 m × 1.8 m box 1.5 m
// high a car, a crown of rough segments vegetation, a line hanging 10 m up a wire, a 12 m mast
// with a 1 m cross arm a pole, a 1 m high, 0.2 m thick wall nothing it could name, and neither
// is a 16 m × 2.6 m canopy 2.9 m up that the growing took for a line (IGN 77050_627760's
// parking lot: a wire before the thinness test). No ground lies under the roof and the car: their
// terrain is the ground within the margin around them. A car-sized box 160 m from any ground
// has no known height and is called a building (what a roof-only crop needs); a surface reaching
// 6 m below the terrain around it is terrain grown into one segment, no building (IGN's La
// Réunion sample: a wooded ravine, one segment, was a "building"); a NaN point is skipped.
TEST(ObjectClasses, ConstructedObjectsGetTheirClasses)
{
  Scene s;
  addTerrain(s, {{-31.0f, -17.0f, -31.0f, -19.0f}, {9.5f, 15.0f, 9.5f, 12.3f}});
  s.rectangle(-30.0f, -18.0f, -30.0f, -20.0f, 6.0f, 0.5f, 1, SegmentKind::Solid);  // roof
  s.rectangle(10.0f, 14.5f, 10.0f, 11.8f, 1.5f, 0.2f, 2, SegmentKind::Solid);      // car
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 800; ++i) {  // crown
    const Eigen::Vector3f d(u(rng), u(rng), u(rng));
    if (d.norm() <= 1.0f)
      s.add(20.0f + 3.0f * d.x(), -20.0f + 3.0f * d.y(), 7.0f + 3.0f * d.z(), 3, SegmentKind::Rough);
  }
  for (float x = -35.0f; x <= 35.0f; x += 0.3f)  // wire
    s.add(x, 30.0f, 10.0f + 0.002f * x * x, 4, SegmentKind::Linear);
  for (float z = 0.0f; z <= 12.0f; z += 0.1f)  // pole
    s.add(0.0f, -10.0f, z, 5, SegmentKind::Linear);
  for (float x = -0.5f; x <= 0.5f; x += 0.1f)
    s.add(x, -10.0f, 11.0f, 5, SegmentKind::Linear);
  for (float x = -20.0f; x <= -15.0f; x += 0.1f)  // low wall
    for (float z = 0.1f; z <= 1.0f; z += 0.1f)
      for (float y : {10.0f, 10.2f})
        s.add(x, y, z, 6, SegmentKind::Wall);

  for (float x = -30.0f; x <= -14.0f; x += 0.2f)  // canopy
    for (float y = 20.0f; y <= 22.6f; y += 0.2f)
      s.add(x, y, 2.9f, 7, SegmentKind::Linear);

  s.rectangle(200.0f, 204.5f, 0.0f, 1.8f, 1.5f, 0.2f, 8, SegmentKind::Solid);  // far "car"
  for (float x = 30.0f; x <= 38.0f; x += 0.25f)    // a slope from 6 m below the terrain to 6 m
    for (float y = 30.0f; y <= 38.0f; y += 0.25f)  // above it: terrain, not a building
      s.add(x, y, 1.5f * (x - 34.0f), 9, SegmentKind::Solid);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  s.add(nan, 0.0f, nan, 2, SegmentKind::Solid, true);

  const std::vector<ObjectClass> c = s.classify();
  ASSERT_EQ(c.size(), 10u);
  EXPECT_EQ(c[0], ObjectClass::Ground);
  EXPECT_EQ(c[1], ObjectClass::Building);
  EXPECT_EQ(c[2], ObjectClass::Car);
  EXPECT_EQ(c[3], ObjectClass::Vegetation);
  EXPECT_EQ(c[4], ObjectClass::Wire);
  EXPECT_EQ(c[5], ObjectClass::Pole);
  EXPECT_EQ(c[6], ObjectClass::Unclassified);
  EXPECT_EQ(c[7], ObjectClass::Unclassified);
  EXPECT_EQ(c[8], ObjectClass::Building);
  EXPECT_EQ(c[9], ObjectClass::Unclassified);
}

// A roof wider than the ground filter's largest window passes the filter: its segments are of
// the ground kind. Standing 8 m above the ground around it, it is a building; a courtyard at
// the terrain's level beside the terrain, cut off from it, stays ground. (PDAL's sample_c: one
// roof over most of the tile.)
TEST(ObjectClasses, RoofThatPassedTheGroundFilterIsABuilding)
{
  Scene s;
  addTerrain(s);
  s.rectangle(-20.0f, 20.0f, -20.0f, 20.0f, 8.0f, 0.5f, 1, SegmentKind::Ground, true);
  s.rectangle(41.0f, 47.0f, 0.0f, 6.0f, 0.1f, 0.5f, 2, SegmentKind::Ground, true);
  const std::vector<ObjectClass> c = s.classify();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], ObjectClass::Ground);
  EXPECT_EQ(c[1], ObjectClass::Building);
  EXPECT_EQ(c[2], ObjectClass::Ground);
}

// On a hillside of 35° (z = 0.7 x) heights are taken above the terrain's plane, not above the
// median of the ground around: the upper half of the slope, grown into its own ground object,
// is no roof standing over the lower half; a flat roof 6–13 m above the slope is a building, a
// car-sized box 1.5 m above it a car, and an 8 m × 8 m layer of shrubs 1 m above it (grown as
// a surface) nothing it could name, nor a surface holding both the slope and shrubs whose tops
// reach 2.5 m (its median lies on the slope). (IGN's target_cloud_crop: a mountain slope at
// 2 550 m was a building.)
TEST(ObjectClasses, HeightsFollowASlope)
{
  Scene s;
  const auto slope = [](float x) { return 0.7f * x; };
  const auto inHole = [](float x, float y) {
    return (x >= -21.0f && x <= -9.0f && y >= 9.0f && y <= 21.0f) ||
           (x >= 9.5f && x <= 15.0f && y >= -20.5f && y <= -17.7f);
  };
  for (float x = -40.0f; x <= 40.0f; x += 0.5f)
    for (float y = -40.0f; y <= 40.0f; y += 0.5f)
      if (!inHole(x, y))
        s.add(x, y, slope(x), x < 0.0f ? 0 : 1, SegmentKind::Ground, true);
  s.rectangle(-20.0f, -10.0f, 10.0f, 20.0f, slope(-10.0f) + 6.0f, 0.5f, 2, SegmentKind::Solid);
  for (float x = 10.0f; x <= 14.5f; x += 0.2f)  // car
    for (float y = -20.0f; y <= -18.2f; y += 0.2f)
      s.add(x, y, slope(x) + 1.5f, 3, SegmentKind::Solid);
  for (float x = 20.0f; x <= 28.0f; x += 0.25f)  // shrubs along the slope
    for (float y = 20.0f; y <= 28.0f; y += 0.25f)
      s.add(x, y, slope(x) + 1.0f, 4, SegmentKind::Solid);
  int i = 0;  // terrain and shrubs grown into one surface: 30 % of it 2.5 m up, the rest 0.2 m
  for (float x = -30.0f; x <= -24.0f; x += 0.25f)
    for (float y = -30.0f; y <= -24.0f; y += 0.25f)
      s.add(x, y, slope(x) + (i++ % 10 < 3 ? 2.5f : 0.2f), 5, SegmentKind::Solid);
  const std::vector<ObjectClass> c = s.classify();
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0], ObjectClass::Ground);
  EXPECT_EQ(c[1], ObjectClass::Ground);
  EXPECT_EQ(c[2], ObjectClass::Building);
  EXPECT_EQ(c[3], ObjectClass::Car);
  EXPECT_EQ(c[4], ObjectClass::Unclassified);
  EXPECT_EQ(c[5], ObjectClass::Unclassified);
}

// Without any ground point the height tests cannot run: a flat object of more than
// min_building_area is a building (a roof-only crop), a 2 m × 2 m one nothing it could name;
// inputs of unequal sizes give no classes at all.
TEST(ObjectClasses, NoTerrainAndBadSizes)
{
  Scene s;
  s.rectangle(0.0f, 12.0f, 0.0f, 10.0f, 6.0f, 0.5f, 0, SegmentKind::Solid);
  s.rectangle(20.0f, 22.0f, 0.0f, 2.0f, 1.5f, 0.2f, 1, SegmentKind::Solid);
  const std::vector<ObjectClass> c = s.classify();
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], ObjectClass::Building);
  EXPECT_EQ(c[1], ObjectClass::Unclassified);
  std::vector<char> short_ground(s.ground.begin(), s.ground.end() - 1);
  EXPECT_TRUE(classifyObjects(s.points, s.labels, s.kinds, short_ground, {}).empty());
  EXPECT_EQ(std::string(pcl_ls3d::segmentation::toString(ObjectClass::Car)), "car");
  EXPECT_EQ(pcl_ls3d::segmentation::lasCode(ObjectClass::Building), 6);
  EXPECT_EQ(pcl_ls3d::segmentation::lasCode(ObjectClass::Unclassified), 1);
}

// A parked car scans as rough as a shrub (IGN LiDAR HD car parks): with the returns known, a
// rough car-sized object whose pulses had one return each is a car; the same object with half
// its points from multi-return pulses is a shrub, and so is it when the returns are unknown. A
// crown 6 m across at the car's height is vegetation even with single returns (not car-sized in
// plan), and a car-sized rough object 3.5 m up (a crown on a trunk) too. Flags not one per
// point give no classes.
TEST(ObjectClasses, OpaqueCarSizedRoughObjectIsACar)
{
  Scene s;
  addTerrain(s, {{9.5f, 15.0f, 9.5f, 12.3f}});
  std::mt19937 rng(5);
  addRoughBox(s, rng, {10.0f, 10.0f, 1.4f}, 4.5f, 1.8f, 1);    // car
  addRoughBox(s, rng, {-25.0f, 10.0f, 1.4f}, 4.5f, 1.8f, 2);   // shrub of the car's size
  addRoughBox(s, rng, {20.0f, -20.0f, 1.4f}, 6.0f, 6.0f, 3);   // crown
  addRoughBox(s, rng, {-25.0f, -20.0f, 3.5f}, 4.5f, 1.8f, 4);  // small crown on a trunk
  std::vector<char> multiple(s.points.size(), 0);
  for (std::size_t p = 0; p < s.points.size(); ++p)
    multiple[p] = s.labels[p] == 2 && p % 2 == 0;

  const std::vector<ObjectClass> with = classifyObjects(s.points, s.labels, s.kinds, s.ground, {}, multiple);
  ASSERT_EQ(with.size(), 5u);
  EXPECT_EQ(with[0], ObjectClass::Ground);
  EXPECT_EQ(with[1], ObjectClass::Car);
  EXPECT_EQ(with[2], ObjectClass::Vegetation);
  EXPECT_EQ(with[3], ObjectClass::Vegetation);
  EXPECT_EQ(with[4], ObjectClass::Vegetation);
  const std::vector<ObjectClass> without = s.classify();
  ASSERT_EQ(without.size(), 5u);
  EXPECT_EQ(without[1], ObjectClass::Vegetation);
  multiple.pop_back();
  EXPECT_TRUE(classifyObjects(s.points, s.labels, s.kinds, s.ground, {}, multiple).empty());
}

// Cars parked nose to tail with gaps under the growth radius grow into one rough object longer
// than any car (IGN 77050_627755: two cars, 7.9 m × 1.7 m, 7 % multi-return points). Opaque, as
// wide as a car and as low: cars. The same strip with half its pulses passing through is a
// hedge, a wider one no row of cars, a higher one no car.
TEST(ObjectClasses, OpaqueRowOfCarsIsCars)
{
  Scene s;
  addTerrain(s, {{9.5f, 22.3f, 9.5f, 12.3f}});
  std::mt19937 rng(6);
  addRoughBox(s, rng, {10.0f, 10.0f, 1.4f}, 12.0f, 1.8f, 1);    // three cars in a row
  addRoughBox(s, rng, {-30.0f, 10.0f, 1.4f}, 12.0f, 1.8f, 2);   // hedge of the row's size
  addRoughBox(s, rng, {-30.0f, -20.0f, 1.4f}, 12.0f, 4.5f, 3);  // wider than a car
  addRoughBox(s, rng, {10.0f, -20.0f, 3.5f}, 12.0f, 1.8f, 4);   // higher than a car
  addRoughBox(s, rng, {-38.0f, 30.0f, 1.4f}, 40.0f, 1.8f, 5);   // a dense hedge, 40 m long
  std::vector<char> multiple(s.points.size(), 0);
  for (std::size_t p = 0; p < s.points.size(); ++p)
    multiple[p] = s.labels[p] == 2 && p % 2 == 0;

  const std::vector<ObjectClass> with = classifyObjects(s.points, s.labels, s.kinds, s.ground, {}, multiple);
  ASSERT_EQ(with.size(), 6u);
  EXPECT_EQ(with[1], ObjectClass::Car);
  EXPECT_EQ(with[2], ObjectClass::Vegetation);
  EXPECT_EQ(with[3], ObjectClass::Vegetation);
  EXPECT_EQ(with[4], ObjectClass::Vegetation);
  EXPECT_EQ(with[5], ObjectClass::Vegetation);
}

// IMRG end to end on a generated 100 m scene with buildings, trees, shrubs, cars and a power
// line: every point takes its object's class, scored against the generator's ASPRS labels
// (vegetation 3-5, towers 15 as poles, cars 64). Measured on this seed: F1 ground 0.998,
// building 0.998, vegetation 0.975, wire 0.964, car 1.000; towers recall 0.77 (their rough
// members join no pole), pole precision 0.92. Planes take the class of their object.
TEST(ObjectClasses, ImrgClassesOnAGeneratedScene)
{
  pcl_ls3d::synth::SceneSettings settings;
  settings.seed = 4;
  settings.size_x = settings.size_y = 100.0;
  const auto scene = pcl_ls3d::synth::makeScene(settings);
  ASSERT_TRUE(scene.cloud && scene.cloud->size() > 50000u);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : *scene.cloud)
    cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  using Segmenter = pcl_ls3d::MultiRuleRegionGrowing<pcl::PointXYZ>;
  Segmenter seg;
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> objects;
  seg.extract(objects);
  const auto& classes = seg.getClusterClasses(Segmenter::Level::Objects);
  ASSERT_EQ(classes.size(), objects.size());

  const auto groupOf = [](int code) {
    return code >= 3 && code <= 5 ? 5 : code;  // vegetation as one class
  };
  std::vector<int> predicted(cloud->size(), 0);
  for (std::size_t o = 0; o < objects.size(); ++o)
    for (const auto i : objects[o].indices)
      predicted[static_cast<std::size_t>(i)] = pcl_ls3d::segmentation::lasCode(classes[o]);
  std::map<int, std::size_t> tp, fp, fn;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const int ref = groupOf(scene.cloud->points[i].classification), pred = predicted[i];
    if (ref == pred)
      ++tp[ref];
    else {
      ++fn[ref];
      ++fp[pred];
    }
  }
  const auto f1 = [&](int c) { return 2.0 * tp[c] / (2.0 * tp[c] + fp[c] + fn[c]); };
  EXPECT_GE(f1(2), 0.95) << "ground";
  EXPECT_GE(f1(6), 0.95) << "building";
  EXPECT_GE(f1(5), 0.95) << "vegetation";
  EXPECT_GE(f1(14), 0.90) << "wire";
  EXPECT_GE(f1(64), 0.90) << "car";
  EXPECT_GE(static_cast<double>(tp[15]) / (tp[15] + fn[15]), 0.6) << "tower recall";
  EXPECT_GE(static_cast<double>(tp[15]) / (tp[15] + fp[15]), 0.85) << "pole precision";

  // Every shrub, however few its points, is vegetation: the object holding most of it is a
  // vegetation object and holds more than half of it. (The fragment absorption after the
  // assembly used to put bushes of under 30 points, which the assembly had left alone, back
  // into the ground: 49 of 60 shrubs on seeds 1-3.)
  std::vector<int> object_of(cloud->size(), -1);
  for (std::size_t o = 0; o < objects.size(); ++o)
    for (const auto i : objects[o].indices)
      object_of[static_cast<std::size_t>(i)] = static_cast<int>(o);
  std::size_t shrubs = 0, shrubs_kept = 0;
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    if (scene.objects[k].type != pcl_ls3d::synth::ObjectType::SHRUB)
      continue;
    std::map<int, std::size_t> held;
    std::size_t size = 0;
    for (std::size_t i = 0; i < scene.object_id.size(); ++i)
      if (scene.object_id[i] == static_cast<int>(k)) {
        ++size;
        ++held[object_of[i]];
      }
    if (size < 5)
      continue;
    const auto most = std::max_element(held.begin(), held.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    // A shrub at a lattice tower's foot joins the tower's rough members (its object is a pole;
    // two on this seed): not counted.
    if (most->first >= 0 && classes[static_cast<std::size_t>(most->first)] == ObjectClass::Pole)
      continue;
    ++shrubs;
    shrubs_kept += most->first >= 0 && 2 * most->second > size &&
                   classes[static_cast<std::size_t>(most->first)] == ObjectClass::Vegetation;
  }
  EXPECT_GT(shrubs, 10u);
  EXPECT_EQ(shrubs_kept, shrubs);

  // Plane level: a class per plane, and the roof planes (plane_id >= 0 majority) are building
  // planes.
  const auto& planes = seg.getClusters(Segmenter::Level::Planes);
  const auto& plane_classes = seg.getClusterClasses(Segmenter::Level::Planes);
  ASSERT_EQ(plane_classes.size(), planes.size());
  std::size_t roof_planes = 0, roof_planes_building = 0;
  for (std::size_t p = 0; p < planes.size(); ++p) {
    std::size_t on_roof = 0;
    for (const auto i : planes[p].indices)
      on_roof += scene.plane_id[static_cast<std::size_t>(i)] >= 0;
    if (2 * on_roof > planes[p].indices.size() && planes[p].indices.size() >= 100) {
      ++roof_planes;
      roof_planes_building += plane_classes[p] == ObjectClass::Building;
    }
  }
  EXPECT_GT(roof_planes, 0u);
  EXPECT_EQ(roof_planes_building, roof_planes);

  // MRG assembles no objects and so gives no classes.
  seg.setMode(Segmenter::Mode::MRG);
  seg.extract(objects);
  EXPECT_TRUE(seg.getClusterClasses(Segmenter::Level::Objects).empty());
}

namespace {

/// A real LAS file through IMRG with its defaults: the points (with their reference classes),
/// the objects and their classes.
struct RealRun
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> las;
  std::vector<pcl::PointIndices> objects;
  std::vector<ObjectClass> classes;
};

/// IMRG's objects and classes of a LAS file; with \a use_returns its numbers of returns too.
void
segmentRealFile(const std::string& path, RealRun& run, bool use_returns = false)
{
  pcl_ls3d::io::CloudInfo info;
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::loadCloud(path, run.las, info, error)) << error;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : run.las)
    cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  using Segmenter = pcl_ls3d::MultiRuleRegionGrowing<pcl::PointXYZ>;
  Segmenter seg;
  seg.setInputCloud(cloud);
  if (use_returns) {
    std::vector<std::uint8_t> returns;
    for (const auto& p : run.las)
      returns.push_back(p.number_of_returns);
    seg.setNumberOfReturns(returns);
  }
  seg.extract(run.objects);
  run.classes = seg.getClusterClasses(Segmenter::Level::Objects);
  ASSERT_EQ(run.classes.size(), run.objects.size());
}

}  // namespace

// Real data (skipped without ../shared/data): PDAL's sample_c is one roof over most of an
// 84 m × 75 m tile, wider than what the ground filter removes beside so little terrain, so its
// segments are of the ground kind; the roof stands 10-25 m above the terrain around it and
// must come out as a building, the terrain as ground (measured: building recall 1.000, ground
// recall 0.980; before the raised-ground rule the roof's 12 305 points were called ground).
TEST(ObjectClasses, SampleCRoofIsABuildingNotGround)
{
  const std::string path = std::string(PCL_LS3D_SHARED_DATA_DIR) + "/segmentation/pdal__sample_c.las";
  if (!std::ifstream(path).good())
    GTEST_SKIP() << "shared data not found: " << path << "; skipped";
  RealRun run;
  segmentRealFile(path, run);
  if (HasFatalFailure())
    return;
  const auto& las = run.las;
  const auto& objects = run.objects;
  const auto& classes = run.classes;
  std::map<int, std::size_t> hits, total;  // per reference code: points given that class
  for (std::size_t o = 0; o < objects.size(); ++o)
    for (const auto i : objects[o].indices) {
      const int ref = las[static_cast<std::size_t>(i)].classification;
      ++total[ref];
      hits[ref] += pcl_ls3d::segmentation::lasCode(classes[o]) == ref;
    }
  ASSERT_GT(total[6], 10000u);
  EXPECT_GE(static_cast<double>(hits[6]) / total[6], 0.95) << "building recall";
  EXPECT_GE(static_cast<double>(hits[2]) / total[2], 0.9) << "ground recall";
}

// Real data (skipped without ../shared/data): IGN LiDAR HD tile 77050_627760 (a check tile:
// the multiple-return share was chosen on 77050_627755 and 77055_627755) has a car park whose
// cars IGN leaves in class 1 and IMRG grows as rough objects. Objects of at least 20 points,
// by their majority reference code: without returns 5 class-1 objects are named car, with
// them 14 (measured), while vegetation named car goes from 0 to 1. Returns not one per point
// make extract() fail.
TEST(ObjectClasses, ReturnsNameParkedCarsOnARealTile)
{
  const std::string path = std::string(PCL_LS3D_SHARED_DATA_DIR) +
                           "/registration/ign_lidarhd/test_data_77050_627760_LA93_IGN69.las";
  if (!std::ifstream(path).good())
    GTEST_SKIP() << "shared data not found: " << path << "; skipped";
  const auto cars = [](const RealRun& run, bool vegetation) {
    std::size_t n = 0;
    for (std::size_t o = 0; o < run.objects.size(); ++o) {
      std::map<int, std::size_t> votes;  // 1 unclassified, 3 vegetation (3-5), 0 anything else
      for (const auto i : run.objects[o].indices) {
        const int c = run.las[static_cast<std::size_t>(i)].classification;
        ++votes[c == 1 ? 1 : (c >= 3 && c <= 5) ? 3 : 0];
      }
      const auto top = std::max_element(votes.begin(), votes.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
      n += run.objects[o].indices.size() >= 20 && run.classes[o] == ObjectClass::Car &&
           top->first == (vegetation ? 3 : 1);
    }
    return n;
  };
  RealRun without, with;
  segmentRealFile(path, without);
  segmentRealFile(path, with, true);
  if (HasFatalFailure())
    return;
  EXPECT_GE(cars(with, false), 10u);
  EXPECT_GE(cars(with, false), 2 * cars(without, false));
  EXPECT_LE(cars(with, true), 2u);

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : with.las)
    cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
  pcl_ls3d::MultiRuleRegionGrowing<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfReturns(std::vector<std::uint8_t>(cloud->size() - 1, 2));
  std::vector<pcl::PointIndices> objects;
  seg.extract(objects);
  EXPECT_TRUE(objects.empty());
}

// Real data (skipped without ../shared/data): IGN's La Réunion sample is a wooded ravine with
// 60 m of relief in 50 m; IMRG grows it into one segment of 99.5 % of the points, which the
// classes called a building (its top 31 m above the ground filter's few points) before the
// rule that a building stands on the terrain: its low points lie 7 m below it. Unclassified,
// and pcl_ls3d_segment says that no structure was found.
TEST(ObjectClasses, WoodedRavineIsNoBuilding)
{
  const std::string path =
      std::string(PCL_LS3D_SHARED_DATA_DIR) + "/registration/ign_lidarhd/sample_lareunion_epsg2975.las";
  if (!std::ifstream(path).good())
    GTEST_SKIP() << "shared data not found: " << path << "; skipped";
  RealRun run;
  segmentRealFile(path, run);
  if (HasFatalFailure())
    return;
  const auto& objects = run.objects;
  const auto& classes = run.classes;
  std::size_t building = 0;
  for (std::size_t o = 0; o < objects.size(); ++o)
    building += classes[o] == ObjectClass::Building ? objects[o].indices.size() : 0;
  EXPECT_LT(building, run.las.size() / 10) << "points called building";

  const pcl_ls3d_test::ToolRun r =
      pcl_ls3d_test::runToolMerged("pcl_ls3d_segment", path, ::testing::TempDir());
  ASSERT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("no structure was found"), std::string::npos) << r.out;
}
