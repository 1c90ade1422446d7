// Tests of the truth JSON: parseable, and the numbers are the generators' truth.
#include <pcl_ls3d/synth/truth_json.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace pcl_ls3d;
using namespace pcl_ls3d::synth;

// "transformation" is the global 4×4 (row-major) and "parameters" rotate about the origin.
TEST(Synth, PairTruthJson)
{
  RegistrationPairSettings s;
  s.size_x = s.size_y = 40.0;
  s.origin = Eigen::Vector3d(5e5, 5e6, 50.0);
  const auto pair = makeRegistrationPair(s);
  const auto j = nlohmann::json::parse(truthJson(pair, s));
  const Eigen::Matrix4d G = pair.globalTruthMatrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(j["transformation"][r][c].get<double>(), G(r, c));
  EXPECT_EQ(j["parameters"]["kappa"].get<double>(), s.truth.kappa);
  EXPECT_EQ(j["parameters"]["m"].get<double>(), s.truth.m);
  EXPECT_EQ(j["parameters_frame_origin"][1].get<double>(), 5e6);
  // The global parameters keep the angles and scale; only t changes.
  EXPECT_NEAR(j["parameters_global"]["phi"].get<double>(), s.truth.phi, 1e-12);
  EXPECT_EQ(j["counts"]["source"].get<std::size_t>(), pair.source->size());
  EXPECT_EQ(j["seed"].get<int>(), 1);
}

TEST(Synth, StripAndLiTruthJson)
{
  StripSettings s;
  s.strip_length = 60.0;
  s.swath_width = 40.0;
  s.density = 1.0;
  const auto block = makeStripBlock(s);
  const auto j = nlohmann::json::parse(truthJson(block, s));
  ASSERT_EQ(j["strips"].size(), 3u);
  EXPECT_TRUE(j["strips"][0]["fixed"].get<bool>());
  EXPECT_EQ(j["strips"][2]["parameters"]["omega"].get<double>(), block.strips[2].transform.omega);
  EXPECT_EQ(j["strips"][1]["point_source_id"].get<int>(), 2);

  LiSurfaceSettings ls;
  const auto li = makeLiSurface(ls);
  const auto k = nlohmann::json::parse(truthJson(li, ls));
  EXPECT_EQ(k["deformation"]["indices"].size(), li.deformed_indices.size());
  EXPECT_EQ(k["deformation"]["mask"].size(), 2500u);
  EXPECT_EQ(k["settings"]["position"].get<std::string>(), "upper_right");
  EXPECT_EQ(k["parameters"]["tx"].get<double>(), ls.truth.t.x());
}

TEST(Synth, SceneTruthJson)
{
  SceneSettings s;
  s.size_x = s.size_y = 60.0;
  s.density = 2.0;
  const auto scene = makeScene(s);
  const auto j = nlohmann::json::parse(truthJson(scene, s));
  EXPECT_EQ(j["objects"].size(), scene.objects.size());
  EXPECT_EQ(j["counts"]["points"].get<std::size_t>(), scene.cloud->size());
  EXPECT_EQ(j["counts"]["by_class"]["2"].get<std::size_t>(), scene.classCounts().at(2));
}
