#include "matching_steps.h"

#include <pcl_ls3d/adjustment/surface_noise.h>
#include <pcl_ls3d/rules/local_tin.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {
namespace detail {

bool
overlapCentroid(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
                const Eigen::Matrix4d& guess, double max_distance, Eigen::Vector3d& centroid,
                Eigen::AlignedBox3d& box, std::vector<int>& inside)
{
  for (std::size_t i = 0; i < target.size(); ++i) {
    const Eigen::Vector3d p = target.point(static_cast<int>(i));
    if (p.allFinite())
      box.extend(p);
  }
  if (box.isEmpty())
    return false;
  const double margin = std::min(max_distance, 0.1 * box.diagonal().norm());
  Eigen::AlignedBox3d grown = box;
  grown.min().array() -= margin;
  grown.max().array() += margin;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  inside.clear();
  for (std::size_t i = 0; i < source.size(); ++i)
    if (grown.contains((guess * source[i].homogeneous()).head<3>())) {
      const Eigen::Vector3d& p = source[i];
      inside.push_back(static_cast<int>(i));
      sum += p;
      ++n;
    }
  if (n == 0)
    return false;
  centroid = sum / static_cast<double>(n);
  return true;
}

bool
setUpPair(const std::vector<Eigen::Vector3d>& source, const TargetSurface& target,
          const Eigen::Matrix4d& guess, const AdjustmentSettings& settings, PairSetup& setup,
          std::vector<Eigen::Vector3d>& reduced)
{
  Eigen::Vector3d o_s;
  if (!overlapCentroid(source, target, guess, settings.max_correspondence_distance, o_s,
                       setup.target_box, setup.inside))
    return false;
  const Eigen::Vector3d o_t = (guess * o_s.homogeneous()).head<3>();
  ParameterBlock& block = setup.source;
  block.input_origin = o_s;
  block.output_origin = o_t;
  block.values = SimilarityTransform::fromMatrix(globalToLocal(guess, o_s, o_t)).vector();
  block.values.head<3>().setZero();  // o_t = guess(o_s) by construction
  block.apriori_values = settings.apriori_from_guess ? block.values : settings.apriori_values;
  block.apriori_weights = settings.apriori_weights;
  for (int i = 0; i < 7; ++i)
    if (settings.isFixed(i))
      block.values[i] = block.apriori_values[i];
  setup.target = ParameterBlock::fixedIdentity(o_t);

  reduced.resize(source.size());
  setup.radius = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    reduced[i] = source[i] - o_s;
    setup.radius = std::max(setup.radius, reduced[i].norm());
    setup.source_box.extend(reduced[i]);
  }
  return true;
}

namespace {

// "collinear", "coincident" or "" for the k nearest target points of `query`: a direction
// within the tolerance below is rounding.
std::string
neighbourhoodDegeneracy(const TargetSurface& target, const Eigen::Vector3d& query)
{
  std::vector<int> idx;
  std::vector<float> sq;
  const int n = target.nearestKSearch(query, 16, idx, sq);
  if (n <= 0)
    return "";
  // The iterative solver, not tin::neighbourhoodPca's closed form: it resolves eigenvalues
  // many orders below the largest, which the rounding tolerance below needs.
  Eigen::Vector3d mean;
  const Eigen::Matrix3d cov = tin::neighbourhoodCovariance(target, idx, n, mean);
  const Eigen::Vector3d spread =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov, Eigen::EigenvaluesOnly)
          .eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  // 1e-5 of the neighbourhood's length, plus the rounding of float coordinates (~1e-7 of their
  // size: not 1e-5 of it, which is metres at projected coordinates).
  const double tolerance = 1e-5 * spread[2] + 1e-7 * mean.cwiseAbs().maxCoeff();
  if (spread[2] <= tolerance)
    return "coincident";
  return spread[1] <= tolerance ? "collinear" : "";
}

}  // namespace

std::string
degenerateTarget(const std::vector<Eigen::Vector3d>& source, const std::vector<int>& inside,
                 const Eigen::Matrix4d& guess, const TargetSurface& target)
{
  if (inside.empty())
    return "";
  // Up to 64 source points spread over the overlap; all must meet a degenerate target.
  const std::size_t step = std::max<std::size_t>(1, inside.size() / 64);
  bool collinear = false;
  for (std::size_t i = 0; i < inside.size(); i += step) {
    const Eigen::Vector3d q = (guess * source[static_cast<std::size_t>(inside[i])].homogeneous()).head<3>();
    const std::string kind = neighbourhoodDegeneracy(target, q);
    if (kind.empty())
      return "";
    collinear = collinear || kind == "collinear";
  }
  return collinear ? "collinear" : "coincident";
}

std::string
degenerateTargetReason(const std::vector<Eigen::Vector3d>& source, const std::vector<int>& inside,
                       const Eigen::Matrix4d& guess, const TargetSurface& target,
                       const std::string& target_name, const std::string& source_name)
{
  const std::string degenerate = degenerateTarget(source, inside, guess, target);
  if (degenerate.empty())
    return "";
  return "no observation: the " + target_name + " has no surface the rule can fit where the " +
         source_name + " lies over it (degenerate: its points there are " + degenerate + ")";
}

Vector7d
rankTestScaling(double radius)
{
  const double inv_r = radius > 0.0 ? 1.0 / radius : 1.0;
  Vector7d scaling;
  scaling << 1, 1, 1, inv_r, inv_r, inv_r, inv_r;
  return scaling;
}

double
sourceNoise(const std::vector<Eigen::Vector3d>& reduced, const PairSetup& setup)
{
  const double area = setup.source_box.sizes().head<2>().prod();
  const double density = area > 0.0 ? static_cast<double>(reduced.size()) / area : 0.0;
  if (!(density > 0.0))
    return 0.0;
  return estimateSurfaceNoise(reduced, setup.inside, std::sqrt(30.0 / (M_PI * density)));
}

double
precisionCell(const AdjustmentSettings& settings, const PairSetup& setup, std::size_t target_size)
{
  if (settings.precision_cell > 0.0)
    return settings.precision_cell;
  const double area = setup.target_box.sizes().head<2>().prod();
  return area > 0.0 ? 8.0 * std::sqrt(area / static_cast<double>(target_size)) : 0.0;
}

std::string
fillPrecision(AdjustmentReport& report, const GaussMarkovSolution& sol)
{
  std::string undetermined;
  // σ0 = 0: every residual vanished (a cloud matched to itself or to a superset of itself).
  // The data say nothing about the spread then; σ = 0 would claim a perfect instrument.
  const bool exact_fit = !(sol.sigma0 > 1e-10);  // rounding of identical coordinates: ~1e-16
  if (exact_fit)
    report.precision_model = "not estimable: exact fit, every residual is 0";
  for (int i = 0; i < 7; ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    report.sigmas_formal[i] = sol.sigma0 * std::sqrt(sol.qxx(i, i));
    if (sol.fixed[s])
      report.sigmas[i] = report.sigmas_formal[i] = 0.0;
    else if (!sol.determinable[s]) {
      report.sigmas[i] = report.sigmas_formal[i] = std::numeric_limits<double>::infinity();
      undetermined += (undetermined.empty() ? "" : ", ") + similarityParameterNames()[s];
    }
    else if (exact_fit)
      report.sigmas[i] = report.sigmas_formal[i] = std::numeric_limits<double>::quiet_NaN();
    else
      report.sigmas[i] = std::sqrt(std::max(0.0, report.covariance(i, i)));
    for (int j = 0; j < 7; ++j) {
      const double d = std::sqrt(report.covariance(i, i) * report.covariance(j, j));
      report.correlation(i, j) = d > 0.0 ? report.covariance(i, j) / d : 0.0;
    }
  }
  return undetermined;
}

std::vector<Eigen::Vector3d>
conjugatePoints(const ObservationSet& set, std::size_t most)
{
  std::vector<Eigen::Vector3d> feet;
  const std::size_t step = std::max<std::size_t>(1, set.size() / std::max<std::size_t>(1, most));
  for (std::size_t j = 0; j < set.size() && feet.size() < most; j += step)
    feet.push_back(set[j].foot);
  return feet;
}

std::array<bool, 7>
flags7(const std::vector<bool>& flags)
{
  std::array<bool, 7> out{};
  for (std::size_t i = 0; i < 7 && i < flags.size(); ++i)
    out[i] = flags[i];
  return out;
}

}  // namespace detail
}  // namespace pcl_ls3d
