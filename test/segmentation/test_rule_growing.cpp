/// \file test_rule_growing.cpp
/// \brief The per-set growing rules of (I)MRG (rule_growing.h) on constructed points and
///        features, so that each rule is tested alone.

#include <pcl_ls3d/segmentation/rule_growing.h>

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace sg = pcl_ls3d::segmentation;

// A flat roof (z = 5) and, 0.2 m beside its edge, a parallel surface 0.4 m higher (the top of a
// hedge or crown against the eave, a low roof step): every point planar with a +z normal and a
// small residual, each linked to its neighbours within 0.5 m. The paper's planar rule (normals
// within N_t, distance within the growth radius) grows the roof across the 0.45 m gap into the
// upper surface. A neighbour must also lie on the tangent plane within growth radius × sin N_t
// (0.5 × sin 10° = 0.087 m): the two levels stay two segments; a 5 cm bump inside the roof
// (within that allowance) does not cut it.
TEST(RuleGrowing, PlanarGrowthStaysOnItsTangentPlane)
{
  std::vector<Eigen::Vector3f> points;
  for (float x = 0.f; x <= 4.01f; x += 0.25f)
    for (float y = 0.f; y <= 4.01f; y += 0.25f)
      points.emplace_back(x, y, 5.f + ((x == 2.f && y == 2.f) ? 0.05f : 0.f));
  const std::size_t roof_end = points.size();
  for (float x = 4.2f; x <= 6.01f; x += 0.25f)
    for (float y = 0.f; y <= 4.01f; y += 0.25f)
      points.emplace_back(x, y, 5.4f);

  sg::PointFeatures planar;
  planar.dimensionality = sg::Dimensionality::Planar;
  planar.residual = 0.001f;
  const std::vector<sg::PointFeatures> features(points.size(), planar);
  const std::vector<Eigen::Vector3f> normals(points.size(), Eigen::Vector3f::UnitZ());
  const int k = 24;
  std::vector<int> graph(points.size() * k, -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    int g = 0;
    for (std::size_t j = 0; j < points.size() && g < k; ++j)
      if (j != i && (points[i] - points[j]).norm() <= 0.5f)
        graph[i * k + static_cast<std::size_t>(g++)] = static_cast<int>(j);
  }
  sg::GrowingSettings s;
  s.graph_k = k;
  s.growth_radius = 0.5;
  s.volumetric_radius = 0.25;
  s.residual_threshold = 0.01;

  for (const bool seed_condition : {false, true}) {
    s.use_seed_condition = seed_condition;
    const std::vector<int> label = sg::growRegions(points, features, normals, graph, s);
    ASSERT_EQ(label.size(), points.size());
    const std::set<int> roof(label.begin(), label.begin() + static_cast<long>(roof_end));
    const std::set<int> upper(label.begin() + static_cast<long>(roof_end), label.end());
    EXPECT_EQ(roof.size(), 1u) << "the roof (with its 5 cm bump) is one segment";
    EXPECT_EQ(upper.size(), 1u);
    EXPECT_NE(*roof.begin(), *upper.begin()) << "the roof grew into the surface 0.4 m above it";
  }
}
