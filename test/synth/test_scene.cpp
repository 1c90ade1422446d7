// Tests of makeScene: every class present, labels consistent with geometry, returns, ids.
#include <pcl_ls3d/synth/scene.h>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>

using namespace pcl_ls3d;
using namespace pcl_ls3d::synth;

namespace {

SceneSettings
smallScene()
{
  SceneSettings s;
  s.seed = 11;
  s.size_x = 120.0;
  s.size_y = 100.0;
  s.density = 5.0;
  return s;
}

}  // namespace

// All the promised classes appear, and object ids point at objects of the same class family.
TEST(Synth, SceneClassesAndObjects)
{
  const auto s = smallScene();
  const LabelledScene scene = makeScene(s);
  ASSERT_FALSE(scene.cloud->empty());
  ASSERT_EQ(scene.object_id.size(), scene.cloud->size());
  const auto counts = scene.classCounts();
  for (int c : {2, 3, 4, 5, 6, 14, 15, 64})
    EXPECT_GT(counts.count(c) ? counts.at(c) : 0u, 10u) << "class " << c;
  for (std::size_t i = 0; i < scene.cloud->size(); ++i) {
    const int id = scene.object_id[i];
    const int cls = (*scene.cloud)[i].classification;
    ASSERT_GE(id, 0) << "every generated point belongs to an object";
    const ObjectType t = scene.objects[id].type;
    if (cls == 2) {
      ASSERT_EQ(t, ObjectType::GROUND);
    }
    if (cls >= 3 && cls <= 5) {
      ASSERT_TRUE(t == ObjectType::TREE || t == ObjectType::SHRUB);
    } else {
      ASSERT_EQ(cls, scene.objects[id].classification) << toString(t);
    }
  }
}

// Roof plane ids: every roof point has one, nothing else does; the points of each plane lie on
// one plane (RMS distance to their own least-squares plane within the noise), and each building
// has the planes of its roof type (flat 1, gable 2, hip 4), all hit.
TEST(Synth, SceneRoofPlanes)
{
  auto s = smallScene();
  s.building_settings.per_hectare = 15.0;
  const LabelledScene scene = makeScene(s);
  ASSERT_EQ(scene.plane_id.size(), scene.cloud->size());
  std::vector<Eigen::Vector3d> sum(scene.planes.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> sq(scene.planes.size(), Eigen::Matrix3d::Zero());
  std::vector<std::size_t> n(scene.planes.size(), 0);
  for (std::size_t i = 0; i < scene.cloud->size(); ++i) {
    const int id = scene.plane_id[i];
    const auto& p = (*scene.cloud)[i];
    if (id < 0)
      continue;
    ASSERT_EQ(p.classification, 6);
    ASSERT_EQ(scene.objects[scene.planes[id].object].type, ObjectType::BUILDING);
    const Eigen::Vector3d x = p.getVector3fMap().cast<double>();
    sum[id] += x;
    sq[id] += x * x.transpose();
    ++n[id];
  }
  std::map<int, int> planes_per_building, hips;
  for (std::size_t k = 0; k < scene.planes.size(); ++k) {
    ASSERT_GT(n[k], 20u) << "plane " << k;
    EXPECT_EQ(n[k], scene.planes[k].point_count);
    const Eigen::Vector3d mean = sum[k] / static_cast<double>(n[k]);
    const Eigen::Matrix3d cov = sq[k] / static_cast<double>(n[k]) - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    EXPECT_LT(std::sqrt(std::max(0.0, es.eigenvalues()[0])), 2.0 * s.noise_sigma) << "plane " << k;
    ++planes_per_building[scene.planes[k].object];
    hips[scene.planes[k].object] += scene.planes[k].roof == RoofType::HIP;
  }
  ASSERT_GE(planes_per_building.size(), 3u);
  bool any_hip = false;
  for (const auto& [object, count] : planes_per_building) {
    const RoofType roof = scene
                              .planes[static_cast<std::size_t>(
                                  std::find_if(scene.planes.begin(), scene.planes.end(),
                                               [o = object](const RoofPlane& p) { return p.object == o; }) -
                                  scene.planes.begin())]
                              .roof;
    EXPECT_EQ(count, roofPlaneCount(roof));
    any_hip |= roof == RoofType::HIP;
  }
  EXPECT_TRUE(any_hip);
}

// Geometry: ground on the terrain within noise; vegetation class matches the height above the
// terrain; roofs above it; cars 1.4–1.8 m up; wires high above the ground.
TEST(Synth, SceneLabelsMatchGeometry)
{
  const auto s = smallScene();
  const LabelledScene scene = makeScene(s);
  const Terrain& terrain = scene.surface->terrain();
  const double tol = 6.0 * s.noise_sigma;  // 6 σ: no false failures among ~10^5 points
  for (const auto& p : *scene.cloud) {
    const double above = p.z - terrain.height(p.x, p.y);
    switch (p.classification) {
    case 2:
      ASSERT_LT(std::abs(above), tol);
      break;
    case 3:
      ASSERT_LT(above, s.low_max);
      break;
    case 4:
      ASSERT_TRUE(above >= s.low_max && above < s.medium_max);
      break;
    case 5:
      ASSERT_GE(above, s.medium_max);
      break;
    case 6:
      ASSERT_GT(above, -tol);  // walls start at the ground
      break;
    case 14:
      ASSERT_GT(above, 8.0);  // 25 m towers, sag 3 % of spans ≤ 160 m
      break;
    case 64:
      ASSERT_GT(above, 1.0);
      ASSERT_LT(above, 2.5);  // 1.4–1.8 m above the highest corner on gentle terrain
      break;
    default:
      break;
    }
  }
}

// Multiple returns under trees: return numbers consistent, last returns reach the ground.
TEST(Synth, SceneReturns)
{
  const LabelledScene scene = makeScene(smallScene());
  std::size_t multi = 0, last_ground = 0;
  for (const auto& p : *scene.cloud) {
    ASSERT_GE(p.return_number, 1);
    ASSERT_LE(p.return_number, p.number_of_returns);
    ASSERT_LE(p.number_of_returns, 3);
    if (p.number_of_returns > 1) {
      ++multi;
      last_ground += p.return_number == p.number_of_returns && p.classification == 2;
    }
  }
  EXPECT_GT(multi, 500u);
  EXPECT_GT(last_ground, 100u);
}

TEST(Synth, SceneDeterministic)
{
  auto s = smallScene();
  const LabelledScene a = makeScene(s), b = makeScene(s);
  ASSERT_EQ(a.cloud->size(), b.cloud->size());
  for (std::size_t i = 0; i < a.cloud->size(); i += 3) {
    ASSERT_EQ((*a.cloud)[i].z, (*b.cloud)[i].z);
    ASSERT_EQ((*a.cloud)[i].classification, (*b.cloud)[i].classification);
  }
  s.seed = 12;
  const LabelledScene c = makeScene(s);
  EXPECT_NE((*a.cloud)[0].x, (*c.cloud)[0].x);
  s.medium_max = 0.1;  // below low_max
  EXPECT_TRUE(makeScene(s).cloud->empty());
}
