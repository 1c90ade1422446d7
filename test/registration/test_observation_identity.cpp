// Stage 4 (observation_weighting.h, RobustEstimator::weigh): an estimator sees which source point
// each residual belongs to, under the same index in every iteration. Points planted 2 m above
// the surface must be exactly the observations with the large residuals, iteration after
// iteration, and the indices must be those the report gives for the last iteration.
#include "ls3d_test_utils.h"

#include <gtest/gtest.h>

#include <set>

using namespace pcl_ls3d;

namespace {

bool
planted(int index)
{
  return index % 50 == 0;
}

class RecordingEstimator final : public RobustEstimator
{
public:
  struct Seen
  {
    std::vector<int> points;
    std::vector<double> residuals;
  };
  std::string
  name() const override
  {
    return "recording";
  }
  void
  computeWeights(const Eigen::Ref<const Eigen::VectorXd>& residuals,
                 const Eigen::Ref<const Eigen::VectorXd>& sigma_v, double sigma0,
                 Eigen::Ref<Eigen::VectorXd> weights) const override
  {
    zuo_.computeWeights(residuals, sigma_v, sigma0, weights);
  }
  void
  weigh(const WeightingInput& in, Eigen::Ref<Eigen::VectorXd> weights) const override
  {
    Seen seen;
    for (const Observation& o : *in.observations)
      seen.points.push_back(o.point);
    seen.residuals.assign(in.residuals.data(), in.residuals.data() + in.residuals.size());
    log.push_back(seen);
    computeWeights(in.residuals, in.sigma_v, in.scale, weights);
  }
  mutable std::vector<Seen> log;

private:
  ZuoEstimator zuo_;
};

TEST(ObservationIdentity, EstimatorFollowsPlantedPointsAcrossIterations)
{
  synth::RegistrationPairSettings settings;
  settings.size_x = settings.size_y = 100.0;
  settings.overlap = 0.9;
  settings.noise_sigma = 0.02;
  settings.buildings = false;
  settings.truth = SimilarityTransform((Vector7d() << 0.08, -0.05, 0.03, 5e-4, -3e-4, 8e-4, 1).finished());
  const synth::RegistrationPair pair = synth::makeRegistrationPair(settings);
  ls3d_test::Cloud::Ptr source(new ls3d_test::Cloud(*pair.source));
  for (std::size_t i = 0; i < source->size(); ++i)
    if (planted(static_cast<int>(i)))
      (*source)[i].z += 2.0f;

  auto recorder = std::make_shared<RecordingEstimator>();
  ls3d_test::LS3D ls3d;
  ls3d.setInputSource(source);
  ls3d.setInputTarget(pair.target);
  ls3d.setRobustEstimator(recorder);
  // A reach wide enough to keep the 2 m blunders in view of the estimator (the automatic reach
  // would drop them as soon as σ0 is known, and this test is about what the estimator sees).
  ls3d.setMaxCorrespondenceDistance(5.0);
  ls3d_test::Cloud aligned;
  ls3d.align(aligned);
  ASSERT_TRUE(ls3d.hasConverged()) << ls3d.getReport().message;
  ASSERT_GE(recorder->log.size(), 3u);

  for (std::size_t it = 1; it < recorder->log.size(); ++it) {  // after the first solve
    const auto& seen = recorder->log[it];
    std::size_t planted_seen = 0;
    for (std::size_t j = 0; j < seen.points.size(); ++j) {
      const bool gross = std::abs(seen.residuals[j]) > 1.0;
      EXPECT_EQ(gross, planted(seen.points[j])) << "iteration " << it + 1 << " point " << seen.points[j];
      planted_seen += planted(seen.points[j]);
    }
    EXPECT_GT(planted_seen, 100u);
  }
  // The last two iterations observe (almost) the same points: their indices did not move.
  const auto& last = recorder->log.back();
  const auto& before = recorder->log[recorder->log.size() - 2];
  const std::set<int> previous(before.points.begin(), before.points.end());
  std::size_t common = 0;
  for (int p : last.points)
    common += previous.count(p);
  EXPECT_GT(static_cast<double>(common), 0.99 * static_cast<double>(last.points.size()));
  // The report names the same points (no point was dropped or thinned: indices are cloud indices).
  EXPECT_EQ(std::vector<int>(ls3d.getReport().observation_source_index), last.points);
}

}  // namespace
