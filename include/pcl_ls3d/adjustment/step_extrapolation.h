#pragma once
/// \file step_extrapolation.h
/// \brief Besl & McKay (1992, §IV-C) acceleration of a creeping iteration: when consecutive
///        steps are nearly parallel and each is a steady fraction ρ of the previous one (the
///        creep of closest-point matching), jump to the limit of the geometric series,
///        X += dx ρ/(1 − ρ).

#include <pcl_ls3d/common/similarity_transform.h>

#include <algorithm>

namespace pcl_ls3d {

/// \brief Decides, step by step, whether and how far to extrapolate.
class StepExtrapolator
{
public:
  /// \param[in] step this iteration's change, scaled to comparable units (displacement at the
  ///            edge of the data); \param[in] iteration its number.
  /// \return the factor f to apply as X += f dx (0: no extrapolation). After an extrapolation
  ///         two plain steps are needed before the next one.
  double
  next(const Vector7d& step, int iteration)
  {
    double factor = 0.0;
    const double norm = step.norm(), previous = previous_.norm();
    if (iteration >= last_ + 3 && previous > 0.0 && norm > 0.0) {
      const double rho = norm / previous;
      const double cosine = step.dot(previous_) / (norm * previous);
      if (cosine > 0.98 && rho > 0.3 && rho < 0.97) {
        factor = std::min(10.0, rho / (1.0 - rho));
        last_ = iteration;
      }
    }
    previous_ = step;
    return factor;
  }

private:
  Vector7d previous_ = Vector7d::Zero();
  int last_ = -10;
};

}  // namespace pcl_ls3d
