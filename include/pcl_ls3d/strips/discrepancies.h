#pragma once
/// \file discrepancies.h
/// \brief How well two strips agree: signed normal discrepancies between the stable surfaces
///        of an overlap, measured the same way whatever rule the adjustment used (LND: the
///        distance of a point of one strip to the local quadric of the other, along its normal),
///        with the sign "strip i above strip j" in both directions. And the strips' own noise on
///        the same surfaces (each observed point against its own strip's surface, the point
///        itself left out), the floor the discrepancies can reach after adjustment.
///        (evaluation/surface_discrepancy.h is the rule-free yardstick of the method comparison.)

#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/strips/overlap_selection.h>

#include <Eigen/Core>

#include <array>
#include <memory>
#include <vector>

namespace pcl_ls3d {
namespace strips {

/// \brief Samples of a discrepancy: where (block XY of the observed point, as moved by its
///        strip's pose), how much, and along which surface normal (oriented upwards: moving
///        strip i by t relative to strip j changes a value by normalᵀ t).
struct DiscrepancySamples
{
  std::vector<Eigen::Vector2d> xy;
  std::vector<float> value;
  std::vector<Eigen::Vector3f> normal;

  void
  append(const DiscrepancySamples& o)
  {
    xy.insert(xy.end(), o.xy.begin(), o.xy.end());
    value.insert(value.end(), o.value.begin(), o.value.end());
    normal.insert(normal.end(), o.normal.begin(), o.normal.end());
  }
};

/// \brief The relative translation of strip i against strip j that the discrepancies ask for:
///        least squares over the values within `max_abs` (walls and edges seen from two sides
///        left out), t = −(Σ n nᵀ)⁻¹ Σ n v, with its σ per axis for independent values of
///        spread σ_MAD. Zero with count 0 when there are fewer than 3 values or Σ n nᵀ is
///        singular.
struct AskedTranslation
{
  std::size_t count = 0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
};

AskedTranslation
askedTranslation(const DiscrepancySamples& samples, double max_abs);

/// \brief Summary of a sample: mean, RMS, σ_MAD = 1.4826 MAD and the 5/16/50/84/95 % points.
struct DiscrepancyStatistics
{
  std::size_t count = 0;
  double mean = 0.0, rms = 0.0, sigma_mad = 0.0;
  double p05 = 0.0, p16 = 0.0, p50 = 0.0, p84 = 0.0, p95 = 0.0;
};

DiscrepancyStatistics
discrepancyStatistics(const std::vector<float>& values);

/// \brief Evaluates one overlap (both directions) at given poses.
class DiscrepancyEvaluator
{
public:
  explicit DiscrepancyEvaluator(const OverlapSelection& selection, double max_distance);
  ~DiscrepancyEvaluator();

  /// Signed discrepancies of i relative to j at the poses of both strips.
  DiscrepancySamples
  evaluate(const ParameterBlock& block_i, const ParameterBlock& block_j);

  /// Each strip's own noise: its observed points against its own surface without themselves
  /// (leave one out), positions in block XY. [0]: strip i, [1]: strip j.
  std::array<DiscrepancySamples, 2>
  ownNoise(const ParameterBlock& block_i, const ParameterBlock& block_j);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strips
}  // namespace pcl_ls3d
