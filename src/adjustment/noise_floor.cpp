#include <pcl_ls3d/adjustment/noise_floor.h>
#include <pcl_ls3d/rules/local_tin.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ls3d {

namespace {

// The upper of the two middle values for an even count (nth_element at n/2), as the strips' noise
// floor has always taken it; stats::median() averages the two and would move their figures.
double
upperMedian(std::vector<double> v)
{
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

NeighbourPairs
sequentialNeighbours(const PairMatcher& matcher, const ObservationSet& set, double reach)
{
  // Only the first observation of each point (its surface normal): ICP's tangent axes are
  // perpendicular to it by construction, not by noise.
  NeighbourPairs pairs;
  const double reach2 = reach * reach;
  std::size_t prev = set.size();
  for (std::size_t k = 0; k < set.size(); ++k) {
    if (set[k].component != 0)
      continue;
    const std::size_t last = prev;
    prev = k;
    if (last != set.size() &&
        (matcher.position(set[last]) - matcher.position(set[k])).squaredNorm() <= reach2)
      pairs.emplace_back(last, k);
  }
  return pairs;
}

double
fittedNormalVariance(const TargetSurface& target, const ObservationSet& set, int neighbours)
{
  std::vector<double> variance;
  std::vector<int> index;
  std::vector<float> d2;
  const std::size_t stride = std::max<std::size_t>(1, set.size() / kNoiseAnchors);
  for (std::size_t k = 0; k < set.size(); k += stride) {
    const Observation& o = set[k];
    const double len = o.direction.norm();
    if (o.component != 0 || !(len > 0.0))
      continue;
    const int count = target.nearestKSearch(o.foot, neighbours, index, d2);
    double height = 0.0;
    Eigen::Vector2d slope, slope_variance;
    if (tin::quadricPatch(target, index, count, o.foot, o.direction / len, height, slope, nullptr, nullptr,
                          &slope_variance) &&
        slope_variance.allFinite())
      variance.push_back(0.5 * slope_variance.sum());
  }
  return variance.size() < 20 ? 0.0 : upperMedian(std::move(variance));
}

double
normalNoiseVariance(const ObservationSet& set, const NeighbourPairs& neighbours)
{
  std::vector<double> d2;
  d2.reserve(neighbours.size());
  for (const auto& [k, l] : neighbours) {
    Eigen::Vector3d ua = set[k].direction.normalized(), ub = set[l].direction.normalized();
    if (ua.dot(ub) < 0.0)
      ub = -ub;
    d2.push_back((ua - ub).squaredNorm());
  }
  if (d2.size() < 20)
    return 0.0;
  return upperMedian(std::move(d2)) / (4.0 * std::log(2.0));
}

std::vector<bool>
noiseDominated(const Matrix7d& N, const Matrix7d& M, const Vector7d& apriori_weights, const Vector7d& scaling,
               double share)
{
  std::vector<bool> flagged(7, false);
  std::vector<int> free;
  for (int q = 0; q < 7; ++q)
    if (!std::isinf(apriori_weights[q]))
      free.push_back(q);
  while (!free.empty() && M.norm() > 0.0) {
    const auto m = static_cast<Eigen::Index>(free.size());
    // Scaled to displacements at the data's edge so that N is well conditioned for the
    // Cholesky inside the generalised eigensolver.
    Eigen::MatrixXd Ns(m, m), Ms(m, m);
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index b = 0; b < m; ++b) {
        const int qa = free[static_cast<std::size_t>(a)], qb = free[static_cast<std::size_t>(b)];
        const double s = scaling[qa] * scaling[qb];
        Ns(a, b) = s * (N(qa, qb) + (a == b ? apriori_weights[qa] : 0.0));
        Ms(a, b) = s * M(qa, qb);
      }
    // The solver factorises N without telling whether it could: a singular N (a column the
    // geometry leaves empty) is the rank test's to flag, not this one's.
    if (Eigen::LLT<Eigen::MatrixXd>(Ns).info() != Eigen::Success)
      break;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ms, Ns);
    if (es.info() != Eigen::Success)
      break;
    Eigen::Index top = 0;
    if (!(es.eigenvalues().maxCoeff(&top) > share))
      break;
    Eigen::Index dominant = 0;
    es.eigenvectors().col(top).cwiseAbs().maxCoeff(&dominant);
    flagged[static_cast<std::size_t>(free[static_cast<std::size_t>(dominant)])] = true;
    free.erase(free.begin() + dominant);
  }
  return flagged;
}

void
holdAtStart(const std::vector<bool>& held, const Eigen::VectorXd& start, GaussMarkovProblem& problem)
{
  for (std::size_t g = 0; g < held.size(); ++g)
    if (held[g]) {
      const auto i = static_cast<Eigen::Index>(g);
      problem.current[i] = start[i];
      problem.apriori_values[i] = start[i];
      problem.apriori_weights[i] = std::numeric_limits<double>::infinity();
    }
}

void
reportHeldUndeterminable(const std::vector<bool>& held, GaussMarkovSolution& sol)
{
  for (std::size_t g = 0; g < held.size() && g < sol.fixed.size(); ++g)
    if (held[g]) {
      sol.fixed[g] = false;
      sol.determinable[g] = false;
    }
}

}  // namespace pcl_ls3d
