#include <pcl_ls3d/estimators/robust_scale.h>
#include <pcl_ls3d/sample_consensus/subset_search.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ls3d {

namespace {

/// SplitMix64: a tiny, fully specified generator; subset k has stream (seed, k).
class Stream
{
public:
  Stream(std::uint32_t seed, std::uint64_t k)
      : s_((static_cast<std::uint64_t>(seed) << 32) ^ (k * 0x9E3779B97F4A7C15ull))
  {}
  std::uint64_t
  next()
  {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, n).
  std::size_t
  below(std::size_t n)
  {
    return static_cast<std::size_t>((next() >> 11) % n);
  }

private:
  std::uint64_t s_;
};

/// The observations subsets are drawn from (points with a conjugate) and ranked on.
struct SearchData
{
  std::vector<int> points;             // epoch points with at least one observation
  std::vector<int> scored;             // observation indices subsets are ranked on
  LinearizedMatching::RowMatrix rows;  // rows of `scored`
  Eigen::VectorXd l;                   // distances of `scored`
};

SearchData
prepare(const LinearizedMatching& lin, const SubsetSearchSettings& s)
{
  SearchData d;
  const int n_points = static_cast<int>(lin.reducedPoints().size());
  for (int i = 0; i < n_points; ++i)
    if (lin.observationOf(i) >= 0)
      d.points.push_back(i);
  const std::size_t m = lin.size();
  d.scored.resize(m);
  std::iota(d.scored.begin(), d.scored.end(), 0);
  if (s.score_points > 0 && m > s.score_points) {  // fixed random subsample (partial shuffle)
    Stream rng(s.seed, 0xFFFFFFFFull);
    for (std::size_t i = 0; i < s.score_points; ++i)
      std::swap(d.scored[i], d.scored[i + rng.below(m - i)]);
    d.scored.resize(s.score_points);
    std::sort(d.scored.begin(), d.scored.end());
  }
  d.rows.resize(static_cast<Eigen::Index>(d.scored.size()), 7);
  d.l.resize(static_cast<Eigen::Index>(d.scored.size()));
  for (std::size_t k = 0; k < d.scored.size(); ++k) {
    d.rows.row(static_cast<Eigen::Index>(k)) = lin.rows().row(d.scored[k]);
    d.l[static_cast<Eigen::Index>(k)] = lin.distances()[d.scored[k]];
  }
  return d;
}

/// Observations of p distinct random points; false when there are fewer than p points.
bool
drawSubset(const SearchData& d, const LinearizedMatching& lin, int p, Stream& rng, std::vector<int>& obs)
{
  if (d.points.size() < static_cast<std::size_t>(p))
    return false;
  int chosen[64];
  int count = 0;
  while (count < p) {
    const int point = d.points[rng.below(d.points.size())];
    if (std::find(chosen, chosen + count, point) == chosen + count)
      chosen[count++] = point;
  }
  obs.clear();
  for (int k = 0; k < count; ++k)
    for (int j = 0; j < lin.countOf(chosen[k]); ++j)
      obs.push_back(lin.observationOf(chosen[k]) + j);
  return true;
}

/// A candidate kept for the final round.
struct Candidate
{
  double criterion;
  int subset;
  Vector7d X;
  std::vector<int> sample;
  bool
  operator<(const Candidate& o) const
  {
    return criterion < o.criterion || (criterion == o.criterion && subset < o.subset);
  }
};

/// Keeps the K best candidates (sorted).
void
keepBest(std::vector<Candidate>& best, Candidate c, int K)
{
  best.insert(std::upper_bound(best.begin(), best.end(), c), std::move(c));
  if (static_cast<int>(best.size()) > K)
    best.pop_back();
}

double
worstKept(const std::vector<Candidate>& best, int K)
{
  return static_cast<int>(best.size()) < K ? std::numeric_limits<double>::infinity() : best.back().criterion;
}

/// The K best of all threads' candidates (sorted).
std::vector<Candidate>
mergeCandidates(std::vector<std::vector<Candidate>>& best, int K)
{
  std::vector<Candidate> all;
  for (auto& b : best)
    for (auto& c : b)
      keepBest(all, std::move(c), K);
  return all;
}

/// Residuals of the scored observations under X.
void
scoredResiduals(const SearchData& d, const LinearizedMatching& lin, const Vector7d& X, Eigen::VectorXd& v)
{
  const Vector7d dx = X - lin.linearizationPoint();
  v.resize(d.l.size());
  v.noalias() = d.rows * dx;
  v += d.l;
}

/// med v² over v (lower median), or +inf as soon as it cannot be below `bound`.
double
medianSquared(const Eigen::VectorXd& v, double bound, bool early_exit, std::vector<double>& sq)
{
  const std::size_t m = static_cast<std::size_t>(v.size());
  const std::size_t mid = (m - 1) / 2;
  const std::size_t limit = m - mid;  // this many values ≥ bound ⇒ median ≥ bound
  sq.resize(m);
  std::size_t at_or_above = 0;
  for (std::size_t j = 0; j < m; ++j) {
    const double s = v[static_cast<Eigen::Index>(j)] * v[static_cast<Eigen::Index>(j)];
    sq[j] = s;
    if (early_exit && s >= bound && ++at_or_above >= limit)
      return std::numeric_limits<double>::infinity();
  }
  std::nth_element(sq.begin(), sq.begin() + static_cast<std::ptrdiff_t>(mid), sq.end());
  return sq[mid];
}

/// Mean of the h smallest v², and (optionally) their indices into v.
double
trimmedMeanSquared(const Eigen::VectorXd& v, std::size_t h, std::vector<std::pair<double, int>>& buf,
                   std::vector<int>* chosen)
{
  const std::size_t m = static_cast<std::size_t>(v.size());
  buf.resize(m);
  for (std::size_t j = 0; j < m; ++j)
    buf[j] = {v[static_cast<Eigen::Index>(j)] * v[static_cast<Eigen::Index>(j)], static_cast<int>(j)};
  h = std::min(h, m);
  std::nth_element(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(h - 1), buf.end());
  double sum = 0.0;
  if (chosen)
    chosen->resize(h);
  for (std::size_t j = 0; j < h; ++j) {
    sum += buf[j].first;
    if (chosen)
      (*chosen)[j] = buf[j].second;
  }
  return sum / static_cast<double>(h);
}

int
threadCount()
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

int
threadId()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace

int
subsetsForConfidence(double contamination, double confidence, int sample_size)
{
  const double eps = std::min(0.999, std::max(0.0, contamination));
  const double P = std::min(1.0 - 1e-12, std::max(0.0, confidence));
  const double clean = std::pow(1.0 - eps, std::max(1, sample_size));
  if (clean >= 1.0)
    return 1;
  const double m = std::log(1.0 - P) / std::log(1.0 - clean);
  return static_cast<int>(std::min(1e8, std::ceil(m)));
}

int
defaultSubsets(double contamination, int sample_size)
{
  const int m = subsetsForConfidence(contamination, 0.999, sample_size);
  return std::max(m, contamination > 0.4 ? 3000 : 600);
}

namespace {
std::size_t
coverageCount(std::size_t n, int p, double coverage)
{
  const auto half = (n + static_cast<std::size_t>(p) + 1) / 2;
  return std::min(n, std::max(half, static_cast<std::size_t>(std::ceil(coverage * static_cast<double>(n)))));
}
}  // namespace

double
lmsCriterion(const LinearizedMatching& lin, const Vector7d& X)
{
  if (lin.size() == 0)
    return std::numeric_limits<double>::infinity();
  Eigen::VectorXd v;
  std::vector<double> sq;
  lin.residuals(X, v);
  return medianSquared(v, std::numeric_limits<double>::infinity(), false, sq);
}

double
ltsCriterion(const LinearizedMatching& lin, const Vector7d& X, double coverage)
{
  if (lin.size() == 0)
    return std::numeric_limits<double>::infinity();
  Eigen::VectorXd v;
  std::vector<std::pair<double, int>> buf;
  lin.residuals(X, v);
  return trimmedMeanSquared(v, coverageCount(lin.size(), lin.freeParameters(), coverage), buf, nullptr);
}

SubsetSearchResult
leastMedianOfSquares(const LinearizedMatching& lin, const SubsetSearchSettings& s)
{
  SubsetSearchResult out;
  const SearchData d = prepare(lin, s);
  out.scored = d.scored.size();
  if (d.points.size() < static_cast<std::size_t>(s.sample_size) || d.scored.empty())
    return out;
  const int K = std::max(1, s.finalists);
  std::vector<std::vector<Candidate>> best(static_cast<std::size_t>(threadCount()));
  int valid = 0;
#pragma omp parallel reduction(+ : valid)
  {
    std::vector<Candidate>& mine = best[static_cast<std::size_t>(threadId())];
    std::vector<int> obs;
    Eigen::VectorXd v;
    std::vector<double> sq;
#pragma omp for schedule(static)
    for (int k = 0; k < s.subsets; ++k) {
      Stream rng(s.seed, static_cast<std::uint64_t>(k) + 1);
      Vector7d X;
      if (!drawSubset(d, lin, s.sample_size, rng, obs) || !lin.fit(obs.data(), obs.size(), X))
        continue;
      ++valid;
      scoredResiduals(d, lin, X, v);
      const double med = medianSquared(v, worstKept(mine, K), s.early_exit, sq);
      if (std::isfinite(med) && med < worstKept(mine, K))
        keepBest(mine, Candidate{med, k, X, obs}, K);
    }
  }
  out.drawn = s.subsets;
  out.valid = valid;
  std::vector<Candidate> all = mergeCandidates(best, K);
  if (all.empty())
    return out;
  // Finalists re-scored on every observation (exact when the ranking used all of them).
  Eigen::VectorXd v;
  std::vector<double> sq;
  for (Candidate& c : all) {
    if (d.scored.size() == lin.size())
      break;
    lin.residuals(c.X, v);
    c.criterion = medianSquared(v, std::numeric_limits<double>::infinity(), false, sq);
  }
  std::sort(all.begin(), all.end());
  const Candidate& win = all.front();
  out.ok = true;
  out.parameters = win.X;
  out.criterion = win.criterion;
  out.best_subset = win.subset;
  out.sample = win.sample;
  out.scale = lmsScale(win.criterion, lin.size(), lin.freeParameters());
  return out;
}

namespace {

/// One thread's buffers for C-steps on the scored observations.
struct ScoredCStepBuffers
{
  std::vector<int> chosen, global;
  Eigen::VectorXd v;
  std::vector<std::pair<double, int>> buf;
};

/// `steps` C-steps from a subset's fit X on the scored observations: X becomes the last fit;
/// returns its trimmed criterion over h of them.
double
scoredCSteps(const SearchData& d, const LinearizedMatching& lin, int steps, std::size_t h, Vector7d& X,
             ScoredCStepBuffers& b)
{
  double crit = std::numeric_limits<double>::infinity();
  for (int c = 0; c <= steps; ++c) {
    scoredResiduals(d, lin, X, b.v);
    crit = trimmedMeanSquared(b.v, h, b.buf, &b.chosen);
    if (c == steps)
      break;
    b.global.resize(b.chosen.size());
    for (std::size_t j = 0; j < b.chosen.size(); ++j)
      b.global[j] = d.scored[static_cast<std::size_t>(b.chosen[j])];
    if (!lin.fit(b.global.data(), b.global.size(), X))
      break;
  }
  return crit;
}

/// The K best subsets after their start C-steps (h_scored of the scored observations kept);
/// `valid` counts the subsets that determined the parameters.
std::vector<Candidate>
ltsCandidates(const SearchData& d, const LinearizedMatching& lin, const SubsetSearchSettings& s,
              std::size_t h_scored, int K, int& valid)
{
  std::vector<std::vector<Candidate>> best(static_cast<std::size_t>(threadCount()));
  int drawn_valid = 0;
#pragma omp parallel reduction(+ : drawn_valid)
  {
    std::vector<Candidate>& mine = best[static_cast<std::size_t>(threadId())];
    std::vector<int> obs;
    ScoredCStepBuffers buffers;
#pragma omp for schedule(static)
    for (int k = 0; k < s.subsets; ++k) {
      Stream rng(s.seed, static_cast<std::uint64_t>(k) + 1);
      Vector7d X;
      if (!drawSubset(d, lin, s.sample_size, rng, obs) || !lin.fit(obs.data(), obs.size(), X))
        continue;
      ++drawn_valid;
      const double crit = scoredCSteps(d, lin, s.start_csteps, h_scored, X, buffers);
      if (std::isfinite(crit) && crit < worstKept(mine, K))
        keepBest(mine, Candidate{crit, k, X, obs}, K);
    }
  }
  valid = drawn_valid;
  return mergeCandidates(best, K);
}

/// A finalist's C-steps on all observations (h kept) until the criterion stops decreasing;
/// returns the number of steps taken.
int
concentrate(const LinearizedMatching& lin, std::size_t h, int max_csteps, Candidate& c)
{
  Eigen::VectorXd v;
  std::vector<std::pair<double, int>> buf;
  std::vector<int> chosen;
  lin.residuals(c.X, v);
  c.criterion = trimmedMeanSquared(v, h, buf, &chosen);
  int steps = 0;
  for (int step = 0; step < max_csteps; ++step) {
    Vector7d X;
    if (!lin.fit(chosen.data(), chosen.size(), X))
      break;
    lin.residuals(X, v);
    std::vector<int> next;
    const double crit = trimmedMeanSquared(v, h, buf, &next);
    ++steps;
    if (!(crit < c.criterion * (1.0 - 1e-12)))
      break;  // C-steps never increase the criterion; equal means converged
    c.criterion = crit;
    c.X = X;
    chosen.swap(next);
  }
  return steps;
}

/// The best finalist (ties to the earlier subset) as the search's result.
void
ltsWinner(const std::vector<Candidate>& all, const std::vector<int>& csteps, std::size_t h, std::size_t m,
          SubsetSearchResult& out)
{
  std::vector<std::size_t> order(all.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a] < all[b]; });
  const Candidate& win = all[order.front()];
  out.ok = true;
  out.parameters = win.X;
  out.criterion = win.criterion;
  out.best_subset = win.subset;
  out.sample = win.sample;
  out.coverage = h;
  out.csteps = csteps[order.front()];
  out.scale = ltsScale(win.criterion, static_cast<double>(h) / static_cast<double>(m));
}

}  // namespace

SubsetSearchResult
leastTrimmedSquares(const LinearizedMatching& lin, const SubsetSearchSettings& s)
{
  SubsetSearchResult out;
  const SearchData d = prepare(lin, s);
  out.scored = d.scored.size();
  const std::size_t m = lin.size();
  if (d.points.size() < static_cast<std::size_t>(s.sample_size) || m == 0)
    return out;
  const int p = lin.freeParameters();
  const std::size_t h_scored = coverageCount(d.scored.size(), p, s.coverage),
                    h = coverageCount(m, p, s.coverage);
  const int K = std::max(1, s.finalists);
  std::vector<Candidate> all = ltsCandidates(d, lin, s, h_scored, K, out.valid);
  out.drawn = s.subsets;
  if (all.empty())
    return out;
  std::vector<int> csteps(all.size(), 0);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t f = 0; f < all.size(); ++f)
    csteps[f] = concentrate(lin, h, s.max_csteps, all[f]);
  ltsWinner(all, csteps, h, m, out);
  return out;
}

}  // namespace pcl_ls3d
