// Robust matching in one call (Li et al. 2001's procedure and the MM-estimator) on Li's surface
// with known truth, and its answers to bad input.
#include "deformation/li_surface_pair.h"

#include <pcl_ls3d/estimators/robust_matching.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/rules/conjugate_rule.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace pcl_ls3d;
using li_test::liSurface;

namespace {

constexpr double kSigma = 20.0;

/// One robust matching of a Li surface pair (mate onto reference) from the identity.
struct LiRun : li_test::LiSurfacePair
{
  using LiSurfacePair::LiSurfacePair;
  RobustMatchingReport
  operator()(RobustMethod method, const Eigen::Matrix4d& guess = Eigen::Matrix4d::Identity()) const
  {
    RobustMatchingSettings s;
    s.method = method;
    return robustMatching(points, indices, *surface, *rule, s, guess);
  }
};

/// A hand-made reference (LZD rule) and epoch, for geometry the Li generator does not make.
struct HandMadePair
{
  HandMadePair(const std::vector<Eigen::Vector3d>& reference, std::vector<Eigen::Vector3d> epoch)
      : points(std::move(epoch))
  {
    pcl::PointCloud<PointLiDAR>::Ptr cloud(new pcl::PointCloud<PointLiDAR>);
    for (const Eigen::Vector3d& p : reference) {
      PointLiDAR q;
      q.getVector3fMap() = p.cast<float>();
      cloud->push_back(q);
    }
    for (std::size_t i = 0; i < points.size(); ++i)
      indices.push_back(static_cast<int>(i));
    pcl::search::KdTree<PointLiDAR>::Ptr tree(new pcl::search::KdTree<PointLiDAR>);
    tree->setInputCloud(cloud);
    surface = std::make_shared<PclTargetSurface<PointLiDAR>>(cloud, tree);
    rule = makeConjugateRule(ConjugateRuleType::LZD);
    std::string why;
    rule->prepare(*surface, &why);
  }

  /// Robust matching from the identity, straight to the high-breakdown start when
  /// `least_squares_start` is false (the path that matches through LinearizedMatching first).
  RobustMatchingReport
  operator()(RobustMethod method, bool least_squares_start, double max_distance = 0.0,
             const Eigen::Matrix4d& guess = Eigen::Matrix4d::Identity()) const
  {
    RobustMatchingSettings s;
    s.method = method;
    s.least_squares_start = least_squares_start;
    if (max_distance > 0.0)
      s.adjustment.max_correspondence_distance = max_distance;
    return robustMatching(points, indices, *surface, *rule, s, guess);
  }

  std::vector<Eigen::Vector3d> points;
  std::vector<int> indices;
  std::shared_ptr<PclTargetSurface<PointLiDAR>> surface;
  ConjugateRule::Ptr rule;
};

/// n × n grid nodes of z = slope x + dz over [x0, x0 + size] × [0, size].
std::vector<Eigen::Vector3d>
tiltedGrid(int n, double x0, double size, double slope, double dz)
{
  std::vector<Eigen::Vector3d> grid;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = x0 + size * i / (n - 1), y = size * j / (n - 1);
      grid.emplace_back(x, y, slope * x + dz);
    }
  return grid;
}

}  // namespace

// 40 % of the surface raised by 25 σ at a corner: least squares is pulled far off, LMS and MM
// recover the truth (every grid node within 0.5 σ) and weigh the deformed nodes out.
TEST(RobustMatching, LmsAndMmRecoverTruthWith40PercentDeformed)
{
  const synth::LiSurface li = liSurface(40.0, 25.0, synth::DeformationPosition::UPPER_RIGHT);
  const LiRun run(li);
  const RobustMatchingReport ls = run(RobustMethod::LEAST_SQUARES);
  // Least squares ends far off, and the quality gate says so (σ0 ≈ 9 × the surfaces' noise).
  ASSERT_TRUE(ls.adjustment.hasEstimate()) << ls.message;
  EXPECT_FALSE(ls.adjustment.quality.trustworthy);
  EXPECT_GT(run.errorSigma(ls.adjustment.transformation), 5.0);
  for (const RobustMethod m : {RobustMethod::LMS, RobustMethod::MM}) {
    const RobustMatchingReport r = run(m);
    ASSERT_EQ(r.termination, TerminationType::CONVERGED) << toString(m) << ": " << r.message;
    EXPECT_LT(run.errorSigma(r.adjustment.transformation), 0.5) << toString(m);
    EXPECT_GE(r.subsets_drawn, m == RobustMethod::LMS ? 3000 : 500) << toString(m);
    EXPECT_GE(r.rounds, 1);
    EXPECT_GT(r.scale, 0.5 * kSigma);
    EXPECT_LT(r.scale, 2.5 * kSigma);
    EXPECT_TRUE(std::isfinite(r.adjustment.sigmas[TZ]) && r.adjustment.sigmas[TZ] > 0.0);
    EXPECT_EQ(r.adjustment.sigmas[SCALE], 0.0);  // fixed (6 parameters)
    // Deformed nodes get weight 0, stable ones mostly 1-ish.
    const AdjustmentReport& a = r.adjustment;
    std::size_t deformed_weighted = 0, deformed = 0;
    for (std::size_t j = 0; j < a.weights.size(); ++j)
      if (li.deformed[static_cast<std::size_t>(a.observation_source_index[j])]) {
        ++deformed;
        deformed_weighted += a.weights[j] > 0.0;
      }
    EXPECT_GT(deformed, 300u);
    EXPECT_EQ(deformed_weighted, 0u) << toString(m);
  }
  // MM's scale is the noise's; LMS's M-step uses the MAD of all residuals (Li eq. 7), inflated.
  EXPECT_NEAR(run(RobustMethod::MM).scale, kSigma, 0.15 * kSigma);
}

// Without deformation every estimator gives the least-squares answer.
TEST(RobustMatching, NoDeformationGivesTheLeastSquaresAnswer)
{
  const synth::LiSurface li = liSurface(0.0, 0.0, synth::DeformationPosition::MIDDLE, 2);
  const LiRun run(li);
  const RobustMatchingReport ls = run(RobustMethod::LEAST_SQUARES);
  ASSERT_TRUE(ls.isSolutionUsable());
  EXPECT_LT(run.errorSigma(ls.adjustment.transformation), 0.25);
  EXPECT_NEAR(ls.scale, kSigma, 0.1 * kSigma);
  for (const RobustMethod m : {RobustMethod::M, RobustMethod::MD, RobustMethod::LMS, RobustMethod::MM}) {
    const RobustMatchingReport r = run(m);
    ASSERT_TRUE(r.isSolutionUsable()) << toString(m);
    Eigen::Matrix3Xd pts(3, static_cast<Eigen::Index>(run.points.size()));
    for (std::size_t i = 0; i < run.points.size(); ++i)
      pts.col(static_cast<Eigen::Index>(i)) = run.points[i];
    const double diff =
        evaluation::computeTransformError(r.adjustment.transformation, ls.adjustment.transformation, pts).max;
    EXPECT_LT(diff, 0.1 * kSigma) << toString(m);
    // M-D's σ̂ is Baarda's σ0 of the Tukey-weighted solve, Σ w v² / (n − u): about 17 % below σ
    // (documented in md_estimator.h); the others are consistent.
    if (m == RobustMethod::MD)
      EXPECT_NEAR(r.scale, 0.83 * kSigma, 0.1 * kSigma);
    else
      EXPECT_NEAR(r.scale, kSigma, 0.1 * kSigma) << toString(m);
  }
}

// A deformation over the whole surface is a vertical shift: it is absorbed by tz (a stated
// result, not a failure), every node fits.
TEST(RobustMatching, EverythingDeformedIsATranslation)
{
  synth::LiSurface li = liSurface(100.0, 10.0, synth::DeformationPosition::MIDDLE);
  const LiRun run(li);
  const RobustMatchingReport r = run(RobustMethod::LMS);
  ASSERT_TRUE(r.isSolutionUsable()) << r.message;
  const Eigen::Vector3d node = run.points[1275];
  const Eigen::Vector3d moved = (r.adjustment.transformation * node.homogeneous()).head<3>();
  const Eigen::Vector3d truth = li.truth.apply(node);
  EXPECT_NEAR(moved.z() - truth.z(), -10.0 * kSigma, 1.0 * kSigma);  // the "deformation" is tz
}

// On nearly flat terrain with its middle raised the all-points least-squares start slides off
// the overlap (to 0 observations); the robust stages then begin at the guess, which the start
// could not improve, and say so. Before: the whole matching failed with the start.
TEST(RobustMatching, StartThatSlidOffIsReplacedByTheGuess)
{
  const LiRun run(li_test::gentleTerrain());
  const RobustMatchingReport r = run(RobustMethod::MM);
  EXPECT_FALSE(r.start.hasEstimate()) << "the case no longer slides off: " << r.start.message;
  ASSERT_TRUE(r.adjustment.hasEstimate()) << r.message;
  EXPECT_NE(r.message.find("the robust stages began at the guess"), std::string::npos) << r.message;
  EXPECT_GT(r.subsets_drawn, 0);
  // Plain least squares has no other answer than its start.
  const RobustMatchingReport ls = run(RobustMethod::LEAST_SQUARES);
  EXPECT_FALSE(ls.adjustment.hasEstimate());
  EXPECT_EQ(ls.termination, r.start.termination);
  // Stopped after 20 iterations the start has an estimate, but with a quarter of its first
  // correspondences left: it slid off, and the robust stages begin at the guess all the same.
  RobustMatchingSettings s;
  s.method = RobustMethod::MM;
  s.adjustment.max_iterations = 20;
  const RobustMatchingReport cut =
      robustMatching(run.points, run.indices, *run.surface, *run.rule, s, Eigen::Matrix4d::Identity());
  ASSERT_TRUE(cut.start.hasEstimate()) << cut.start.message;
  EXPECT_LT(cut.start.quality.observations_kept, 0.5);
  EXPECT_NE(cut.message.find("the least-squares start slid off the overlap"), std::string::npos)
      << cut.message;
  EXPECT_NE(cut.message.find("the robust stages began at the guess"), std::string::npos) << cut.message;
}

// Bad input gets a stated termination and message, never a crash.
TEST(RobustMatching, BadInput)
{
  // Flat reference and epoch: horizontal shifts and κ cannot be determined.
  synth::LiSurfaceSettings flat;
  flat.relief = 0.0;
  flat.deformation_percent = 0.0;
  flat.noise_sigma = 1.0;
  const synth::LiSurface plane = synth::makeLiSurface(flat);
  const LiRun on_plane(plane);
  const RobustMatchingReport ls = on_plane(RobustMethod::LEAST_SQUARES, plane.truth.matrix());
  EXPECT_NE(ls.message.find("undeterminable"), std::string::npos) << ls.message;
  const RobustMatchingReport lms = on_plane(RobustMethod::LMS, plane.truth.matrix());
  EXPECT_FALSE(lms.message.empty());
  if (lms.isSolutionUsable()) {
    EXPECT_NE(lms.message.find("undeterminable"), std::string::npos) << lms.message;
  }

  const synth::LiSurface li = liSurface(10.0, 10.0, synth::DeformationPosition::MIDDLE);
  LiRun run(li);
  // No overlap: the epoch 1e6 units away.
  Eigen::Matrix4d far = Eigen::Matrix4d::Identity();
  far(0, 3) = 1e6;
  const RobustMatchingReport none = run(RobustMethod::LMS, far);
  EXPECT_EQ(none.termination, TerminationType::NO_OVERLAP) << none.message;
  EXPECT_FALSE(none.isSolutionUsable());
  // NaN points are ignored: the same answer as without them.
  LiRun with_nan(li);
  with_nan.points[5] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  with_nan.points[6].x() = std::numeric_limits<double>::infinity();
  const RobustMatchingReport a = run(RobustMethod::MM), b = with_nan(RobustMethod::MM);
  ASSERT_TRUE(b.isSolutionUsable()) << b.message;
  EXPECT_LT(with_nan.errorSigma(b.adjustment.transformation), 0.5);
  EXPECT_LT(run.errorSigma(a.adjustment.transformation), 0.5);
  // Fewer points than the sample size.
  LiRun tiny(li);
  tiny.points.assign(run.points.begin() + 1275, run.points.begin() + 1280);  // mid-grid nodes
  tiny.indices.assign(run.indices.begin() + 1275, run.indices.begin() + 1280);
  const RobustMatchingReport few = tiny(RobustMethod::LMS, li.truth.matrix());
  EXPECT_FALSE(few.isSolutionUsable());
  EXPECT_EQ(few.termination, TerminationType::TOO_FEW_OBSERVATIONS) << few.message;
  // Invalid settings.
  RobustMatchingSettings bad;
  bad.contamination = 0.0;
  std::string why;
  EXPECT_FALSE(bad.isValid(&why));
  EXPECT_FALSE(why.empty());
  const RobustMatchingReport invalid =
      robustMatching(run.points, run.indices, *run.surface, *run.rule, bad, Eigen::Matrix4d::Identity());
  EXPECT_EQ(invalid.termination, TerminationType::INVALID_INPUT);
  // Names.
  RobustMethod m;
  EXPECT_TRUE(parseRobustMethod("LMS", m));
  EXPECT_EQ(m, RobustMethod::LMS);
  EXPECT_TRUE(parseRobustMethod("m-d", m));
  EXPECT_EQ(m, RobustMethod::MD);
  EXPECT_FALSE(parseRobustMethod("ransac", m));
}

// A reference whose points all lie on one line has no surface to match: every estimator says
// so as the pair engine does (TOO_FEW_OBSERVATIONS, "degenerate: ... collinear"), also LMS and
// MM when they match through LinearizedMatching first (no least-squares start), which reported
// "no overlap" before.
TEST(RobustMatching, DegenerateReferenceIsNamedNotNoOverlap)
{
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i <= 400; ++i)
    line.emplace_back(0.05 * i, 0.0, 0.0);
  std::vector<Eigen::Vector3d> epoch;  // a flat strip beside the line, y in [-1, 0]
  for (const Eigen::Vector3d& p : tiltedGrid(41, 0.0, 20.0, 0.0, 0.0))
    epoch.emplace_back(p.x(), 0.05 * p.y() - 1.0, 0.0);
  const HandMadePair pair(line, epoch);
  for (const RobustMethod m : {RobustMethod::LMS, RobustMethod::MM, RobustMethod::MD})
    for (const bool ls_start : {false, true}) {
      const RobustMatchingReport r = pair(m, ls_start);
      EXPECT_EQ(r.termination, TerminationType::TOO_FEW_OBSERVATIONS)
          << toString(m) << (ls_start ? " (ls start): " : ": ") << r.message;
      EXPECT_NE(r.message.find("degenerate"), std::string::npos) << toString(m) << ": " << r.message;
      EXPECT_NE(r.message.find("collinear"), std::string::npos) << toString(m) << ": " << r.message;
      EXPECT_EQ(r.message.find("no overlap"), std::string::npos) << toString(m) << ": " << r.message;
      EXPECT_FALSE(r.isSolutionUsable());
    }
}

// A sound reference without overlap is still no overlap on the same path: epoch beyond the
// reference's box, and epoch over the box but beyond the correspondence distance (no
// conjugate point on a plane that spans a surface).
TEST(RobustMatching, NoOverlapOnASoundReferenceIsNoOverlap)
{
  const std::vector<Eigen::Vector3d> plane = tiltedGrid(41, 0.0, 20.0, 0.5, 0.0);
  const HandMadePair beside(plane, tiltedGrid(21, 100.0, 10.0, 0.5, 0.0));
  const HandMadePair above(plane, tiltedGrid(21, 0.0, 10.0, 0.5, 5.0));  // 5 over it, in its box
  for (const RobustMethod m : {RobustMethod::LMS, RobustMethod::MM}) {
    const RobustMatchingReport far = beside(m, false);
    EXPECT_EQ(far.termination, TerminationType::NO_OVERLAP) << toString(m) << ": " << far.message;
    EXPECT_NE(far.message.find("extent"), std::string::npos) << toString(m) << ": " << far.message;
    const RobustMatchingReport none = above(m, false, 1.0);
    EXPECT_EQ(none.termination, TerminationType::NO_OVERLAP) << toString(m) << ": " << none.message;
    EXPECT_NE(none.message.find("found a conjugate point on the reference (no overlap)"), std::string::npos)
        << toString(m) << ": " << none.message;
    EXPECT_EQ(none.message.find("degenerate"), std::string::npos) << toString(m) << ": " << none.message;
  }
}

// Robust matching alone (the compare tool's path), LMS at 36 % deformed by N(5σ, σ): the
// subset fit and its M-step end 4.5 σ off, and main reported them CONVERGED. The residuals the
// M-step kept scatter by 2.0 σ_d (the noise of neighbouring residuals; right fits on Li's grid:
// at most 1.43): the kept-scale gate, switched on, refuses it. Without it (the default, since
// σ_d underestimates the noise of dense surfaces) it is the old CONVERGED.
TEST(RobustMatching, KeptScaleGateRefusesTheCompromise)
{
  const synth::LiSurface li = liSurface(36.0, 5.0, synth::DeformationPosition::UPPER, 1);
  const LiRun run(li);
  RobustMatchingSettings s;
  s.method = RobustMethod::LMS;
  s.block_start = true;          // as the grid was measured (the analysis' default)
  s.max_kept_scale_ratio = 1.5;  // off by default (dense surfaces, robust_matching.h)
  const RobustMatchingReport gated =
      robustMatching(run.points, run.indices, *run.surface, *run.rule, s, Eigen::Matrix4d::Identity());
  s.max_kept_scale_ratio = 0.0;
  const RobustMatchingReport ungated =
      robustMatching(run.points, run.indices, *run.surface, *run.rule, s, Eigen::Matrix4d::Identity());
  ASSERT_TRUE(ungated.isSolutionUsable()) << ungated.message;
  EXPECT_GT(run.errorSigma(ungated.adjustment.transformation), 2.0)
      << "the case no longer shows the compromise";
  EXPECT_GT(gated.kept_scale, 1.5 * gated.final_neighbour_noise);
  EXPECT_FALSE(gated.isSolutionUsable());
  EXPECT_EQ(gated.termination, TerminationType::UNRELIABLE);
  EXPECT_NE(gated.message.find("the M-step kept"), std::string::npos) << gated.message;
  EXPECT_TRUE(gated.adjustment.hasEstimate());
  // A right fit passes: 40 % by 25 σ (LmsAndMmRecoverTruthWith40PercentDeformed) keeps the noise.
  const LiRun easy(liSurface(40.0, 25.0, synth::DeformationPosition::UPPER_RIGHT));
  RobustMatchingSettings on;
  on.method = RobustMethod::LMS;
  on.max_kept_scale_ratio = 1.5;
  const RobustMatchingReport right =
      robustMatching(easy.points, easy.indices, *easy.surface, *easy.rule, on, Eigen::Matrix4d::Identity());
  ASSERT_TRUE(right.isSolutionUsable()) << right.message;
  EXPECT_LT(right.kept_scale, 1.5 * right.final_neighbour_noise);
}
