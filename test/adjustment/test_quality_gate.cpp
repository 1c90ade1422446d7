// The quality gate's position test (quality_gate.h): a fit whose position σ far exceeds the
// surfaces' noise and whose move lies within that σ is refused; a move the data support, or a
// well-fixed position, is not. Inputs are set by hand, the position σ is checked against an
// independent propagation (a pure translation covariance moves every corner by that σ).
#include <pcl_ls3d/adjustment/quality_gate.h>

#include <gtest/gtest.h>

using namespace pcl_ls3d;

namespace {

struct GateCase
{
  QualityInputs in;
  ObservationSet none;
  AdjustmentSettings settings;

  GateCase(double move, double sigma_t)
  {
    in.sigma0 = 0.6;
    in.source_noise = in.target_noise = 0.5;  // expected noise 0.707
    in.spacing = 1.0;
    in.start = (Vector7d() << 0, 0, 0, 0, 0, 0, 1).finished();
    in.estimate = in.start;
    in.estimate[0] = move;
    in.source_box = Eigen::AlignedBox3d(Eigen::Vector3d(-10, -10, -1), Eigen::Vector3d(10, 10, 1));
    in.covariance.setZero();
    in.covariance.diagonal().head<3>().setConstant(sigma_t * sigma_t);
  }
  TerminationType
  gate(QualityFigures& q, std::string& why) const
  {
    q = measureQuality(in, none);
    q.coverage = 1.0;  // no observations are passed: only the position test is under test
    return applyQualityGate(q, in, false, settings, TerminationType::CONVERGED, why);
  }
};

}  // namespace

TEST(QualityGate, PositionSigmaOfATranslationCovarianceIsItsSigma)
{
  const GateCase c(0.0, 0.3);
  const QualityFigures q = measureQuality(c.in, c.none);
  EXPECT_NEAR(q.position_sigma, 0.3, 1e-6);
}

TEST(QualityGate, AMoveWithinAPoorlyFixedPositionIsRefused)
{
  QualityFigures q;
  std::string why;
  // Moved 5 (7 × the noise) with σ 6 (8.5 × the noise): not determined.
  EXPECT_EQ(GateCase(5.0, 6.0).gate(q, why), TerminationType::UNRELIABLE);
  EXPECT_NE(why.find("do not determine the move"), std::string::npos) << why;
  // The same move with σ 0.1: well determined.
  why.clear();
  EXPECT_EQ(GateCase(5.0, 0.1).gate(q, why), TerminationType::CONVERGED) << why;
  // σ 6 but a move of 30 (5 σ): the data support the move, however weak the geometry.
  why.clear();
  EXPECT_EQ(GateCase(30.0, 6.0).gate(q, why), TerminationType::CONVERGED) << why;
  // σ 1.2 (1.7 × the noise, below the limit 2) and a move of 1: kept (Li's surface with M-D).
  why.clear();
  EXPECT_EQ(GateCase(1.0, 1.2).gate(q, why), TerminationType::CONVERGED) << why;
  // A move within the noise is no move to judge, whatever the σ.
  why.clear();
  EXPECT_EQ(GateCase(0.5, 6.0).gate(q, why), TerminationType::CONVERGED) << why;
}
