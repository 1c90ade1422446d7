#pragma once
/// \file normal_equations.h
/// \brief Accumulated normal equations of V = A X + L, P (Zuo et al. 2012, eq. 8): N = AᵀPA,
///        b = AᵀPL, LᵀPL, in double, summable across threads.

#include <pcl_ls3d/adjustment/similarity_jacobian.h>

#include <cstddef>

namespace pcl_ls3d {

/// \brief N = Σ p aᵀa, b = Σ p aᵀ l, ltpl = Σ p l², n = number of observations with p > 0.
struct NormalEquations
{
  Matrix7d N = Matrix7d::Zero();
  Vector7d b = Vector7d::Zero();
  double ltpl = 0.0;
  std::size_t n = 0;

  /// Adds one observation row a with constant term l and weight p (skipped when p ≤ 0).
  void
  add(const RowVector7d& a, double l, double p)
  {
    if (!(p > 0.0))
      return;
    N.selfadjointView<Eigen::Upper>().rankUpdate(a.transpose(), p);
    b.noalias() += (p * l) * a.transpose();
    ltpl += p * l * l;
    ++n;
  }

  /// Makes N symmetric after rankUpdate filled only its upper triangle.
  void
  symmetrize()
  {
    N.triangularView<Eigen::StrictlyLower>() = N.transpose();
  }

  NormalEquations&
  operator+=(const NormalEquations& o)
  {
    N += o.N;
    b += o.b;
    ltpl += o.ltpl;
    n += o.n;
    return *this;
  }
};

}  // namespace pcl_ls3d
