#pragma once
// Generated strip blocks with known truth for the strip-adjustment tests: the strips, and the
// error of an adjusted strip against its truth (mean displacement over the strip's points).
#include <pcl_ls3d/adjustment/similarity_jacobian.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>
#include <pcl_ls3d/strips/strip_io.h>
#include <pcl_ls3d/synth/strip_block.h>

#include <cmath>

namespace strip_test {

using namespace pcl_ls3d;

struct Block
{
  synth::StripBlock generated;
  std::vector<strips::Strip> strips;
};

inline synth::StripSettings
smallBlock(int n = 3, std::uint32_t seed = 3)
{
  synth::StripSettings s;
  s.seed = seed;
  s.num_strips = n;
  s.strip_length = 240.0;
  s.swath_width = 120.0;
  s.side_overlap = 0.3;
  s.density = 2.0;
  s.noise_sigma = 0.05;
  s.shift_sigma = 0.3;
  s.angle_sigma = 5e-4;
  s.scale_sigma = 0.0;
  return s;
}

inline Block
makeBlock(const synth::StripSettings& s)
{
  Block b;
  b.generated = synth::makeStripBlock(s);
  b.strips = strips::stripsFromCloud(*b.generated.cloud, true);
  return b;
}

/// Mean |T_est x − T_true x| over the strip's points (block coordinates), T_est from the report.
inline double
meanDisplacementError(const Block& b, const strips::StripAdjustmentReport& r, std::size_t k)
{
  const Eigen::Matrix4d est = r.strips[k].transformation;  // block origin 0: file = block
  const Eigen::Matrix4d truth = b.generated.strips[k].transform.matrix();
  double sum = 0.0;
  const strips::Strip& s = b.strips[k];
  for (std::size_t i = 0; i < s.size(); i += 7) {
    const Eigen::Vector4d x = s.blockPoint(i).homogeneous();
    sum += ((est - truth) * x).head<3>().norm();
  }
  return sum / std::ceil(static_cast<double>(s.size()) / 7.0);
}

/// Mean over the strip's points of the σ of T_est x that the report's covariance gives,
/// √trace(J C_k Jᵀ) with J = ∂x'/∂X at the estimate (parameters about the strip's origin): the
/// scale of meanDisplacementError() that the estimate's own precision predicts.
inline double
meanDisplacementSigma(const Block& b, const strips::StripAdjustmentReport& r, std::size_t k)
{
  const strips::StripResult& res = r.strips[k];
  const Eigen::Index first = 7 * static_cast<Eigen::Index>(k);
  const Eigen::Matrix<double, 7, 7> C = r.covariance.block<7, 7>(first, first);
  const SimilarityLinearization at(SimilarityTransform(res.parameters));
  double sum = 0.0;
  const strips::Strip& s = b.strips[k];
  for (std::size_t i = 0; i < s.size(); i += 7) {
    const Matrix37d J = at.jacobian(s.blockPoint(i) - res.origin);
    sum += std::sqrt(std::max(0.0, (J * C * J.transpose()).trace()));
  }
  return sum / std::ceil(static_cast<double>(s.size()) / 7.0);
}

/// The true correction of strip k as parameters about the strip's origin o_k (block frame).
inline Vector7d
trueParameters(const Block& b, std::size_t k)
{
  const SimilarityTransform& T = b.generated.strips[k].transform;
  const Eigen::Vector3d o = b.strips[k].origin;
  Vector7d p = T.vector();
  // x' = T x = o + t' + mR(x − o)  ⇒  t' = T(o) − o.
  p.head<3>() = T.t + T.m * (T.rotation() * o) - o;
  return p;
}

}  // namespace strip_test
