#include <pcl_ls3d/adjustment/omitted_parameters.h>
#include <pcl_ls3d/adjustment/spatial_precision.h>

#include <Eigen/Cholesky>

#include <cmath>

namespace pcl_ls3d {

namespace {

// Rows `omitted` of a u × u matrix.
Eigen::MatrixXd
rowsOf(const Eigen::MatrixXd& m, const std::vector<int>& omitted)
{
  Eigen::MatrixXd out(static_cast<Eigen::Index>(omitted.size()), m.cols());
  for (std::size_t r = 0; r < omitted.size(); ++r)
    out.row(static_cast<Eigen::Index>(r)) = m.row(omitted[r]);
  return out;
}

std::string
inconsistent(const Eigen::MatrixXd& normal, const Eigen::VectorXd& gradient, const Eigen::MatrixXd& qxx,
             const std::vector<int>& omitted)
{
  const Eigen::Index u = normal.rows();
  if (normal.cols() != u || gradient.size() != u || qxx.rows() != u || qxx.cols() != u)
    return "matrices of different sizes";
  if (omitted.empty())
    return "no held-out parameter";
  for (int o : omitted)
    if (o < 0 || o >= u || qxx.row(o).cwiseAbs().maxCoeff() != 0.0)
      return "a held-out parameter is out of range or was estimated";
  if (!normal.allFinite() || !gradient.allFinite() || !qxx.allFinite())
    return "non-finite normal equations";
  return {};
}

}  // namespace

OmittedParameterTest
testOmittedParameters(const Eigen::MatrixXd& normal, const Eigen::VectorXd& gradient,
                      const Eigen::MatrixXd& qxx, const MiddleTermFn& middle, double sigma0,
                      const std::vector<int>& omitted)
{
  OmittedParameterTest test;
  test.message = inconsistent(normal, gradient, qxx, omitted);
  if (!test.message.empty())
    return test;
  const Eigen::Index k = static_cast<Eigen::Index>(omitted.size());
  // Lᵀ = [−N_OE Q_EE | I] (zero in the columns of everything not estimated, as Q is there).
  Eigen::MatrixXd Lt = -rowsOf(normal, omitted) * qxx;
  for (Eigen::Index r = 0; r < k; ++r)
    Lt(r, omitted[static_cast<std::size_t>(r)]) += 1.0;
  const Eigen::MatrixXd K = Lt * normal * Lt.transpose();  // = N_OO − N_OE Q_EE N_EO
  const Eigen::VectorXd s = Lt * gradient;                 // the score with E profiled out
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(0.5 * (K + K.transpose()));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().minCoeff() > 0.0)) {
    test.message = "the observations carry no information on the held-out parameters";
    return test;
  }
  const Eigen::MatrixXd Kinv = ldlt.solve(Eigen::MatrixXd::Identity(k, k));
  const Eigen::VectorXd theta = -Kinv * s;
  // The freed model's cofactor matrix and one-step (block inverse of N_f through K).
  const Eigen::MatrixXd q_freed = qxx + Lt.transpose() * Kinv * Lt;
  const Eigen::VectorXd step = -q_freed * gradient;
  const Eigen::MatrixXd M = middle(step, q_freed);
  if (M.rows() != normal.rows() || M.cols() != normal.cols() || !M.allFinite()) {
    test.message = "no middle term for the sandwich";
    return test;
  }
  const Eigen::MatrixXd formal = sigma0 * sigma0 * Kinv;
  const Eigen::MatrixXd C = notBelowFormal<Eigen::MatrixXd>(Kinv * Lt * M * Lt.transpose() * Kinv, formal);
  if (!theta.allFinite() || !C.allFinite()) {
    test.message = "non-finite estimate of the held-out parameters";
    return test;
  }
  for (Eigen::Index r = 0; r < k; ++r) {
    OmittedParameter p;
    p.index = omitted[static_cast<std::size_t>(r)];
    p.estimate = theta[r];
    p.sigma = std::sqrt(std::max(0.0, C(r, r)));
    p.sigma_formal = std::sqrt(std::max(0.0, formal(r, r)));
    p.z = p.sigma > 0.0 ? p.estimate / p.sigma : 0.0;
    test.parameters.push_back(p);
  }
  const Eigen::LDLT<Eigen::MatrixXd> c_ldlt(C);
  test.statistic = c_ldlt.info() == Eigen::Success ? theta.dot(c_ldlt.solve(theta)) : 0.0;
  test.ok = true;
  return test;
}

}  // namespace pcl_ls3d
