#pragma once
// Shared by the strip-adjustment benchmarks (benchmark_strip_*.cpp): generated blocks turned
// into strips, one adjustment run with its wall time, the error of a strip's correction against
// the generator's truth and the machine's load (memory figures: process_memory.h).
#include <pcl_ls3d/adjustment/similarity_jacobian.h>
#include <pcl_ls3d/strips/strip_block_adjustment.h>
#include <pcl_ls3d/strips/strip_io.h>
#include <pcl_ls3d/synth/strip_block.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace strip_bench {

using namespace pcl_ls3d;

struct Block
{
  synth::StripBlock generated;
  std::vector<strips::Strip> strips;
};

inline Block
makeBlock(const synth::StripSettings& s, bool keep_cloud = false)
{
  Block b;
  b.generated = synth::makeStripBlock(s);
  b.strips = strips::stripsFromCloud(*b.generated.cloud, true);
  if (!keep_cloud)
    b.generated.cloud.reset(new pcl::PointCloud<PointLiDAR>);  // truths kept, points freed
  return b;
}

struct Run
{
  strips::StripAdjustmentReport report;
  bool ok = false;
  std::string error;
  double seconds = 0.0;
};

inline Run
adjust(const std::vector<strips::Strip>& s, const strips::StripAdjustmentSettings& settings)
{
  Run r;
  strips::StripBlockAdjustment adjustment;
  adjustment.setSettings(settings);
  const auto t0 = std::chrono::steady_clock::now();
  r.ok = adjustment.run(s, r.report, r.error);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

/// The true correction of strip k (observed → true, block frame) as a 4 × 4 matrix.
inline Eigen::Matrix4d
trueMatrix(const Block& b, std::size_t k)
{
  return b.generated.strips[k].transform.matrix();
}

/// The true correction of strip k as parameters about the strip's origin o_k.
inline Vector7d
trueParameters(const Block& b, std::size_t k)
{
  const SimilarityTransform& T = b.generated.strips[k].transform;
  const Eigen::Vector3d o = b.strips[k].origin;
  Vector7d p = T.vector();
  p.head<3>() = T.t + T.m * (T.rotation() * o) - o;  // x' = o + t' + mR(x − o)
  return p;
}

/// Displacement of A relative to B over every `step`-th point of strip k: mean |Δ| and |mean Δ|.
struct Displacement
{
  double mean_norm = 0.0, norm_of_mean = 0.0, max_norm = 0.0;
};

inline Displacement
displacement(const Block& b, std::size_t k, const Eigen::Matrix4d& A, const Eigen::Matrix4d& B,
             std::size_t step = 7)
{
  Displacement d;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  const strips::Strip& s = b.strips[k];
  for (std::size_t i = 0; i < s.size(); i += step, ++n) {
    const Eigen::Vector3d delta = ((A - B) * s.blockPoint(i).homogeneous()).head<3>();
    d.mean_norm += delta.norm();
    d.max_norm = std::max(d.max_norm, delta.norm());
    sum += delta;
  }
  if (n > 0) {
    d.mean_norm /= static_cast<double>(n);
    d.norm_of_mean = (sum / static_cast<double>(n)).norm();
  }
  return d;
}

/// Mean over every `step`-th point of strip k of the σ of T_est x that the report's covariance
/// gives, √trace(J C_k Jᵀ) with J = ∂x'/∂X at the estimate (parameters about the strip's origin):
/// the scale of displacement().mean_norm that the estimate's own precision predicts.
inline double
displacementSigma(const Block& b, const strips::StripAdjustmentReport& r, std::size_t k, std::size_t step = 7)
{
  const strips::StripResult& res = r.strips[k];
  const Eigen::Index first = 7 * static_cast<Eigen::Index>(k);
  const Matrix7d C = r.covariance.block<7, 7>(first, first);
  const SimilarityLinearization at(SimilarityTransform(res.parameters));
  double sum = 0.0;
  std::size_t n = 0;
  const strips::Strip& s = b.strips[k];
  for (std::size_t i = 0; i < s.size(); i += step, ++n) {
    const Matrix37d J = at.jacobian(s.blockPoint(i) - (res.origin - r.block_origin));
    sum += std::sqrt(std::max(0.0, (J * C * J.transpose()).trace()));
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

inline double
loadAverage()
{
  std::ifstream in("/proc/loadavg");
  double l = -1.0;
  in >> l;
  return l;
}

}  // namespace strip_bench
