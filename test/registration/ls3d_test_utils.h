#pragma once
// Shared helpers of the LS3D registration tests: small synthetic pairs with known truth and
// error measures against that truth.
#include <pcl_ls3d/registration/least_squares_surface_matching.h>
#include <pcl_ls3d/synth/registration_pair.h>

#include <algorithm>
#include <cmath>

namespace ls3d_test {

using PointT = pcl_ls3d::PointLiDAR;
using Cloud = pcl::PointCloud<PointT>;
using LS3D = pcl_ls3d::LeastSquaresSurfaceMatching<PointT, PointT>;

/// A small terrain pair (no buildings unless asked), default truth of the generator.
inline pcl_ls3d::synth::RegistrationPair
smallPair(std::uint32_t seed, double size, double src_density, double tgt_density, double overlap,
          double noise, double wavelength = 60.0, double relief = 10.0, bool buildings = false)
{
  pcl_ls3d::synth::RegistrationPairSettings s;
  s.seed = seed;
  s.size_x = s.size_y = size;
  s.source_density = src_density;
  s.target_density = tgt_density;
  s.overlap = overlap;
  s.noise_sigma = noise;
  s.buildings = buildings;
  s.wavelength = wavelength;
  s.relief = relief;
  return pcl_ls3d::synth::makeRegistrationPair(s);
}

/// Mean and max displacement |T_est x − T_true x| over the source points [m].
struct DisplacementError
{
  double mean = 0.0, max = 0.0;
};

inline DisplacementError
displacementError(const Cloud& source, const Eigen::Matrix4d& estimate, const Eigen::Matrix4d& truth)
{
  DisplacementError e;
  std::size_t n = 0;
  for (const auto& p : source) {
    const Eigen::Vector4d x(p.x, p.y, p.z, 1.0);
    const double d = ((estimate - truth) * x).head<3>().norm();
    e.mean += d;
    e.max = std::max(e.max, d);
    ++n;
  }
  if (n)
    e.mean /= static_cast<double>(n);
  return e;
}

/// The truth expressed in the reduced frame of a report (comparable with report.parameters).
inline pcl_ls3d::Vector7d
truthInReducedFrame(const pcl_ls3d::AdjustmentReport& r, const pcl_ls3d::SimilarityTransform& truth)
{
  return pcl_ls3d::SimilarityTransform::fromMatrix(
             pcl_ls3d::globalToLocal(truth.matrix(), r.local_origin_source, r.local_origin_target))
      .vector();
}

}  // namespace ls3d_test
