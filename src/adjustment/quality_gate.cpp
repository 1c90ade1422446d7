#include <pcl_ls3d/adjustment/observation_weighting.h>
#include <pcl_ls3d/adjustment/quality_gate.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace pcl_ls3d {

namespace {

// Largest |T_estimate(c) − T_start(c)| over the corners of the source's box.
double
movementOverBox(const Vector7d& start, const Vector7d& estimate, const Eigen::AlignedBox3d& box)
{
  if (box.isEmpty())
    return 0.0;
  const SimilarityTransform a(start), b(estimate);
  double largest = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    largest = std::max(largest, (b.apply(corner) - a.apply(corner)).norm());
  }
  return largest;
}

// Largest 1σ position uncertainty of a corner of the box under the estimate: the covariance
// propagated through the corner's Jacobian (central differences), worst direction and corner.
double
cornerPositionSigma(const Vector7d& estimate, const Matrix7d& covariance, const Eigen::AlignedBox3d& box)
{
  if (box.isEmpty() || !covariance.allFinite())
    return 0.0;
  double largest = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    Eigen::Matrix<double, 3, 7> jacobian;
    for (int i = 0; i < 7; ++i) {
      const double h = 1e-6 * std::max(1.0, std::abs(estimate[i]));
      Vector7d plus = estimate, minus = estimate;
      plus[i] += h;
      minus[i] -= h;
      jacobian.col(i) =
          (SimilarityTransform(plus).apply(corner) - SimilarityTransform(minus).apply(corner)) / (2.0 * h);
    }
    const Eigen::Matrix3d position = jacobian * covariance * jacobian.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(position, Eigen::EigenvaluesOnly);
    largest = std::max(largest, std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff())));
  }
  return largest;
}

std::size_t
distinctPoints(const ObservationSet& set)
{
  std::size_t n = 0;
  int last = -1;
  for (const Observation& o : set)
    if (o.point != last) {
      ++n;
      last = o.point;
    }
  return n;
}

double
medianGradient(const ObservationSet& set)
{
  if (set.empty())
    return 1.0;
  std::vector<double> g;
  g.reserve(set.size());
  for (const Observation& o : set)
    g.push_back(o.direction.norm());
  auto mid = g.begin() + static_cast<std::ptrdiff_t>(g.size() / 2);
  std::nth_element(g.begin(), mid, g.end());
  return *mid;
}

// The σ0 limit applied to the residuals across the surface of a multi-observation rule: on
// PCL's bun0 -> bun4 the ICP rule held a minimum 52° from the truth with σ0 = 1.9 x the noise
// (its tangents, within their sampling offsets, diluted the misfit) and the normal
// components at 3.2 x; at the right fit they are 0.33 x.
std::string
normalResidualReason(const QualityFigures& q, const AdjustmentSettings& s)
{
  if (!(q.normal_sigma_ratio > s.max_sigma0_ratio))
    return "";
  char buf[200];
  std::snprintf(buf, sizeof(buf),
                "the residuals across the surface are %.3g x the surfaces' own noise (limit %.3g; "
                "sigma0 %.3g x averages them with the rule's tangential observations)",
                q.normal_sigma_ratio, s.max_sigma0_ratio, q.sigma0_ratio);
  return buf;
}

std::string
figure(const char* text, double value, double limit)
{
  char buf[160];
  std::snprintf(buf, sizeof(buf), text, value, limit);
  return buf;
}

}  // namespace

QualityFigures
measureQuality(const QualityInputs& in, const ObservationSet& observations)
{
  QualityFigures q;
  q.source_noise = in.source_noise;
  q.target_noise = in.target_noise;
  q.expected_noise = std::sqrt(in.source_noise * in.source_noise + in.target_noise * in.target_noise);
  q.noise_yardstick = std::max(q.expected_noise, 1e-3 * in.spacing);
  q.sigma0_ratio = q.noise_yardstick > 0.0 ? in.sigma0 / q.noise_yardstick : 0.0;
  q.normal_sigma_ratio = q.noise_yardstick > 0.0 ? in.normal_sigma / q.noise_yardstick : 0.0;
  q.coverage = in.candidates > 0
                   ? static_cast<double>(distinctPoints(observations)) / static_cast<double>(in.candidates)
                   : 0.0;
  q.rejected_fraction = in.correspondences > 0 ? static_cast<double>(in.correspondences - in.used) /
                                                     static_cast<double>(in.correspondences)
                                               : 0.0;
  q.movement = movementOverBox(in.start, in.estimate, in.source_box);
  q.position_sigma = cornerPositionSigma(in.estimate, in.covariance, in.source_box);
  q.median_gradient = medianGradient(observations);
  q.start_scale = in.start_scale;
  q.observations_kept = in.start_correspondences > 0 ? static_cast<double>(in.correspondences) /
                                                           static_cast<double>(in.start_correspondences)
                                                     : 1.0;
  q.final_scale = robustScale(observations.distances());
  return q;
}

double
normalComponentSigma(const ObservationSet& observations, const Eigen::VectorXd& weights)
{
  const bool several = std::any_of(observations.begin(), observations.end(),
                                   [](const Observation& o) { return o.component != 0; });
  if (!several || weights.size() != static_cast<Eigen::Index>(observations.size()))
    return 0.0;
  double sw = 0.0, swl2 = 0.0;
  for (std::size_t j = 0; j < observations.size(); ++j) {
    const Observation& o = observations[j];
    const double g2 = o.direction.squaredNorm();
    const double w = weights[static_cast<Eigen::Index>(j)];
    if (o.component != 0 || !(g2 > 0.0) || !(w > 0.0))
      continue;
    sw += w;
    swl2 += w * o.distance * o.distance / g2;
  }
  return sw > 0.0 ? std::sqrt(swl2 / sw) : 0.0;
}

bool
moveUndetermined(const QualityFigures& q, const AdjustmentSettings& s)
{
  return q.position_sigma > s.max_position_sigma_ratio * q.expected_noise && q.movement > q.expected_noise &&
         q.movement < s.min_movement_significance * q.position_sigma;
}

bool
heldOutScaleFlagged(const QualityFigures& q, const AdjustmentSettings& s)
{
  return q.held_out_scale_tested && std::abs(q.held_out_scale_z) > s.held_out_z &&
         q.held_out_scale_effect > s.held_out_noise_factor * q.expected_noise && q.expected_noise > 0.0;
}

namespace {

// Appends one reason to the gate's list.
void
addReason(std::string& reasons, const std::string& r)
{
  reasons += (reasons.empty() ? "" : "; ") + r;
}

// The data fix the source's position far worse than the surfaces' noise, and the move lies
// within that uncertainty ("" when not).
std::string
undeterminedMoveReason(const QualityFigures& q, const AdjustmentSettings& s)
{
  if (!moveUndetermined(q, s))
    return "";
  char buf[320];
  std::snprintf(buf, sizeof(buf),
                "the source moved %.3g, only %.3g x its position sigma %.3g (limit %.3g), which is "
                "%.3g x the surfaces' own noise (limit %.3g): the data do not determine the move",
                q.movement, q.movement / q.position_sigma, q.position_sigma, s.min_movement_significance,
                q.position_sigma / q.expected_noise, s.max_position_sigma_ratio);
  return buf;
}

// The rigid fit holds out a scale the data ask for ("" when not).
std::string
heldOutScaleReason(const QualityFigures& q, const AdjustmentSettings& s)
{
  if (!heldOutScaleFlagged(q, s))
    return "";
  // A scale beyond any plausible one is no missing model parameter: the fit itself is wrong.
  const bool plausible = std::abs(q.held_out_scale) <= s.max_scale_deviation;
  char buf[400];
  std::snprintf(buf, sizeof(buf),
                "the rigid fit holds out a scale the data ask for: freed, m - 1 would be %+.3g ppm, "
                "%.3g x its sigma (limit %.3g), moving the source's edge by %.3g, %.3g x the "
                "surfaces' noise (limit %.3g): %s",
                1e6 * q.held_out_scale, std::abs(q.held_out_scale_z), s.held_out_z, q.held_out_scale_effect,
                q.held_out_scale_effect / q.expected_noise, s.held_out_noise_factor,
                plausible ? "free the scale (-params 7)"
                          : "no plausible scale (max_scale_deviation): the fit itself is in doubt");
  return buf;
}

// Signs that the fit does not match the data: σ0, the residuals across the surface, coverage,
// rejections, and residuals grown since the guess.
void
misfitReasons(const QualityFigures& q, const AdjustmentSettings& s, std::string& reasons)
{
  if (q.sigma0_ratio > s.max_sigma0_ratio)
    addReason(reasons, figure(q.noise_yardstick > q.expected_noise
                                  ? "sigma0 is %.3g x the smallest noise the gate assumes, 0.001 x the point "
                                    "spacing (limit %.3g)"
                                  : "sigma0 is %.3g x the surfaces' own noise (limit %.3g)",
                              q.sigma0_ratio, s.max_sigma0_ratio));
  if (const std::string normal = normalResidualReason(q, s); !normal.empty())
    addReason(reasons, normal);
  if (q.coverage < s.min_coverage)
    addReason(reasons,
              figure("only %.3g of the source points over the target have an observation (limit %.3g)",
                     q.coverage, s.min_coverage));
  if (q.rejected_fraction > s.max_rejected_fraction)
    addReason(reasons, figure("%.3g of the correspondences were rejected (limit %.3g)", q.rejected_fraction,
                              s.max_rejected_fraction));
  // Residuals within the surfaces' own noise are no sign of leaving the data, however small
  // they were at the guess (two spinning scans from the same height: their ground rings
  // coincide in the sensor frames to a fraction of the noise).
  const double start_level = std::max(q.start_scale, q.expected_noise);
  if (q.start_scale > 0.0 && q.final_scale > s.max_scale_growth * start_level)
    addReason(reasons, figure("the residuals ended %.3g x larger than at the initial guess (limit %.3g): the "
                              "adjustment moved away from the data",
                              q.final_scale / start_level, s.max_scale_growth));
}

// Signs that the data do not determine the result: an undetermined move, a slide off the
// overlap, a held-out scale, surfaces steeper than the rule measures.
void
determinationReasons(const QualityFigures& q, const AdjustmentSettings& s, std::string& reasons)
{
  // A move the data do support (significant) is kept, however weak the geometry.
  if (const std::string move = undeterminedMoveReason(q, s); !move.empty())
    addReason(reasons, move);
  if (q.observations_kept < s.min_observations_kept)
    addReason(reasons,
              figure("the adjustment ended with %.3g of the correspondences it started with (limit %.3g): "
                     "the source slid off the overlap",
                     q.observations_kept, s.min_observations_kept));
  if (const std::string scale = heldOutScaleReason(q, s); !scale.empty())
    addReason(reasons, scale);
  if (q.median_gradient > s.max_median_gradient)
    addReason(reasons,
              figure("most observations lie on surfaces steeper than the rule measures (median gradient "
                     "%.3g, limit %.3g): use a normal-distance rule (LND)",
                     q.median_gradient, s.max_median_gradient));
}

}  // namespace

TerminationType
applyQualityGate(QualityFigures& q, const QualityInputs& in, bool scale_estimated,
                 const AdjustmentSettings& s, TerminationType termination, std::string& why)
{
  const double scale_change = std::abs(in.estimate[SCALE] / in.start[SCALE] - 1.0);
  if (scale_estimated && scale_change > s.max_scale_deviation) {
    q.trustworthy = false;
    why += std::string(why.empty() ? "" : "; ") +
           figure("implausible scale: |m - m0| / m0 = %.4g exceeds %.4g (fix the scale, -params 6)",
                  scale_change, s.max_scale_deviation);
    return TerminationType::IMPLAUSIBLE_SCALE;
  }
  std::string reasons;
  misfitReasons(q, s, reasons);
  determinationReasons(q, s, reasons);
  q.trustworthy = reasons.empty();
  if (q.trustworthy)
    return termination;
  const bool stalled = q.movement <= std::max(q.expected_noise, 1e-9);
  why += std::string(why.empty() ? "" : "; ") + "NOT TRUSTWORTHY: " + reasons +
         (stalled ? " (the estimate did not move from the initial guess)" : "");
  return stalled ? TerminationType::STALLED : TerminationType::UNRELIABLE;
}

}  // namespace pcl_ls3d
