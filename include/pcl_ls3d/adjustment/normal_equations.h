#pragma once
/// \file normal_equations.h
/// \brief Accumulated normal equations of V = A X + L, P (Zuo et al. 2012, eq. 8): N = AᵀPA,
///        b = AᵀPL, LᵀPL, in double, summable across threads. Fixed size: 7 for one parameter
///        block (a pair), 14 for the two blocks of one overlap in a strip block adjustment.

#include <pcl_ls3d/adjustment/similarity_jacobian.h>

#include <cstddef>

namespace pcl_ls3d {

/// \brief N = Σ p aᵀa, b = Σ p aᵀ l, ltpl = Σ p l², n = number of observations with p > 0.
template <int Dim>
struct NormalEquationsN
{
  using Matrix = Eigen::Matrix<double, Dim, Dim>;
  using Vector = Eigen::Matrix<double, Dim, 1>;
  using Row = Eigen::Matrix<double, 1, Dim>;

  Matrix N = Matrix::Zero();
  Vector b = Vector::Zero();
  double ltpl = 0.0;
  std::size_t n = 0;

  /// Adds one observation row a with constant term l and weight p (skipped when p ≤ 0).
  void
  add(const Row& a, double l, double p)
  {
    if (!(p > 0.0))
      return;
    N.template selfadjointView<Eigen::Upper>().rankUpdate(a.transpose(), p);
    b.noalias() += (p * l) * a.transpose();
    ltpl += p * l * l;
    ++n;
  }

  /// Makes N symmetric after rankUpdate filled only its upper triangle.
  void
  symmetrize()
  {
    N.template triangularView<Eigen::StrictlyLower>() = N.transpose();
  }

  NormalEquationsN&
  operator+=(const NormalEquationsN& o)
  {
    N += o.N;
    b += o.b;
    ltpl += o.ltpl;
    n += o.n;
    return *this;
  }
};

/// One parameter block (the pair adjustment).
using NormalEquations = NormalEquationsN<7>;
/// Two parameter blocks [source | target] of one overlap (strip block adjustment).
using PairNormalEquations = NormalEquationsN<14>;

}  // namespace pcl_ls3d
