#include <pcl_ls3d/sample_consensus/linearized_matching.h>

#include <pcl_ls3d/adjustment/normal_equations.h>
#include <pcl_ls3d/adjustment/similarity_jacobian.h>

#include "adjustment/matching_steps.h"  // the engine's pair set-up
#include "rules/target_overlap.h"       // ... and its degeneracy check

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

bool
LinearizedMatching::reset(const std::vector<Eigen::Vector3d>& points, const TargetSurface& reference,
                          const ConjugateRule& rule, const AdjustmentSettings& settings,
                          const Eigen::Matrix4d& guess, std::string* why, TerminationType* failure)
{
  auto fail = [why, failure](TerminationType type, const std::string& reason) {
    if (why)
      *why = reason;
    if (failure)
      *failure = type;
    return false;
  };
  // The engine's pair set-up: o_s is the centroid of the points over the reference's box.
  detail::PairSetup setup;
  if (!guess.allFinite() || !detail::setUpPair(points, reference, guess, settings, setup, reduced_))
    return fail(TerminationType::NO_OVERLAP,
                "no epoch point falls over the reference's extent under the initial guess");
  block_ = setup.source;
  target_block_ = setup.target;
  problem_ = GaussMarkovProblem(7);
  problem_.apriori_values = block_.apriori_values;
  problem_.apriori_weights = block_.apriori_weights;
  problem_.determinability_threshold = settings.determinability_threshold;
  problem_.scaling = rankTestScaling(setup.radius);
  matcher_.reset(reduced_, reference, rule, settings.max_correspondence_distance);
  if (!relinearize(block_.values)) {
    // Points over the reference and still no conjugate point: a reference without a surface
    // there (collinear, coincident) is named as the engine names it, not taken for no overlap.
    const std::string degenerate =
        detail::degenerateTargetReason(points, setup.inside, guess, reference, "reference", "epoch");
    if (!degenerate.empty())
      return fail(TerminationType::TOO_FEW_OBSERVATIONS, degenerate);
    return fail(TerminationType::NO_OVERLAP,
                "no epoch point found a conjugate point on the reference (no overlap)");
  }
  return true;
}

bool
LinearizedMatching::relinearize(const Vector7d& X)
{
  block_.values = X;
  x0_ = X;
  problem_.current = X;
  matcher_.match(BlockLinearization(block_), BlockLinearization(target_block_), PairMatcher::Sampling());
  rebuildRows();
  return l_.size() > 0;
}

void
LinearizedMatching::rebuildRows()
{
  const ObservationSet& set = matcher_.observations();
  const Eigen::Index m = static_cast<Eigen::Index>(set.size());
  rows_.resize(m, 7);
  l_.resize(m);
  first_.assign(reduced_.size(), -1);
  count_.assign(reduced_.size(), 0);
#pragma omp parallel for schedule(static)
  for (Eigen::Index j = 0; j < m; ++j) {
    const Observation& o = set[static_cast<std::size_t>(j)];
    rows_.row(j) = matcher_.sourceRow(o);
    l_[j] = o.distance;
  }
  for (Eigen::Index j = 0; j < m; ++j) {
    const auto p = static_cast<std::size_t>(set[static_cast<std::size_t>(j)].point);
    if (first_[p] < 0)
      first_[p] = static_cast<int>(j);
    ++count_[p];
  }
}

Vector7d
LinearizedMatching::parametersOf(const Eigen::Matrix4d& T) const
{
  return SimilarityTransform::fromMatrix(globalToLocal(T, block_.input_origin, block_.output_origin))
      .vector();
}

Eigen::Matrix4d
LinearizedMatching::matrixOf(const Vector7d& X) const
{
  return localToGlobal(SimilarityTransform(X).matrix(), block_.input_origin, block_.output_origin);
}

int
LinearizedMatching::freeParameters() const
{
  return freeParameterCount(block_.apriori_weights);
}

bool
LinearizedMatching::fit(const int* obs, std::size_t count, Vector7d& X) const
{
  NormalEquations ne;
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Index j = obs[k];
    ne.add(rows_.row(j), l_[j], 1.0);
  }
  ne.symmetrize();
  const GaussMarkovSolution sol = solveGaussMarkov(ne, problem_);
  if (!sol.ok || sol.redundancy < 0 || sol.unknowns < freeParameters())
    return false;
  X = x0_ + Vector7d(sol.dx);
  return X.allFinite();
}

bool
LinearizedMatching::fitWeighted(const Eigen::VectorXd& weights, Vector7d& X,
                                GaussMarkovSolution* solution) const
{
  NormalEquations ne;
  const Eigen::Index m = l_.size();
#pragma omp parallel
  {
    NormalEquations local;
#pragma omp for schedule(static) nowait
    for (Eigen::Index j = 0; j < m; ++j)
      local.add(rows_.row(j), l_[j], weights[j]);
#pragma omp critical
    ne += local;
  }
  ne.symmetrize();
  GaussMarkovSolution sol = solveGaussMarkov(ne, problem_);
  const bool ok = sol.ok && sol.unknowns >= freeParameters() && sol.redundancy >= 0;
  if (ok)
    X = x0_ + Vector7d(sol.dx);
  if (solution)
    *solution = std::move(sol);
  return ok && X.allFinite();
}

std::vector<double>
LinearizedMatching::pointResiduals(const Eigen::VectorXd& v) const
{
  std::vector<double> out(reduced_.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < out.size(); ++i)
    if (first_[i] >= 0 && first_[i] < v.size())
      out[i] = v[first_[i]];
  return out;
}

void
LinearizedMatching::residuals(const Vector7d& X, Eigen::VectorXd& v) const
{
  const Vector7d dx = X - x0_;
  v.resize(l_.size());
  v.noalias() = rows_ * dx;
  v += l_;
}

}  // namespace pcl_ls3d
