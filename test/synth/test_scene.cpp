// Tests of makeScene: every class present, labels consistent with geometry, returns, ids.
#include <pcl_ls3d/synth/scene.h>

#include <gtest/gtest.h>

#include <cmath>

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
    if (id < 0) {
      ASSERT_EQ(cls, 2);
      continue;
    }
    const ObjectType t = scene.objects[id].type;
    if (cls >= 3 && cls <= 5)
      ASSERT_TRUE(t == ObjectType::TREE || t == ObjectType::SHRUB);
    else
      ASSERT_EQ(cls, scene.objects[id].classification) << toString(t);
  }
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
