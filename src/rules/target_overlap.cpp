#include "target_overlap.h"

#include <pcl_ls3d/rules/local_tin.h>

#include <Eigen/Eigenvalues>

#include <algorithm>

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
  const Eigen::Vector3d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov, Eigen::EigenvaluesOnly)
                                     .eigenvalues()
                                     .cwiseMax(0.0)
                                     .cwiseSqrt();  // ascending
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
  return "no observation: the " + target_name + " has no surface the rule can fit where the " + source_name +
         " lies over it (degenerate: its points there are " + degenerate + ")";
}

}  // namespace detail
}  // namespace pcl_ls3d
