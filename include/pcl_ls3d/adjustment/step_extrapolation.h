#pragma once
/// \file step_extrapolation.h
/// \brief Besl & McKay (1992, §IV-C) acceleration of a creeping iteration: when consecutive
///        steps are nearly parallel and each is a steady fraction ρ of the previous one (the
///        creep of closest-point matching), jump to the limit of the geometric series,
///        X += dx ρ/(1 − ρ).
///
/// The geometric series describes the iteration only once it creeps: the correspondences
/// change little from one step to the next, so each step is a steady fraction of the last. A
/// step that moves the source by more than the target's point spacing is still the approach,
/// where equal steps say nothing about the distance left: on PCL's bun0 → bun4 the ICP rule
/// turned 8.7° per step with ρ = 0.95 and the jump of 10 steps (87°) landed in another
/// minimum, 52° from the truth. Such steps are not extrapolated (max_step).

#include <pcl_ls3d/common/similarity_transform.h>

#include <algorithm>
#include <limits>

namespace pcl_ls3d {

/// \brief Decides, step by step, whether and how far to extrapolate.
class StepExtrapolator
{
public:
  /// \param[in] max_step largest step (same units as next()'s) that may be creep; larger steps
  ///            are never extrapolated. Infinite: no limit.
  explicit StepExtrapolator(double max_step = std::numeric_limits<double>::infinity()) : max_step_(max_step)
  {}

  /// \param[in] step this iteration's change, scaled to comparable units (displacement at the
  ///            edge of the data); \param[in] iteration its number.
  /// \return the factor f to apply as X += f dx (0: no extrapolation). After an extrapolation
  ///         two plain steps are needed before the next one.
  double
  next(const Vector7d& step, int iteration)
  {
    double factor = 0.0;
    const double norm = step.norm(), previous = previous_.norm();
    if (iteration >= last_ + 3 && previous > 0.0 && norm > 0.0 && norm <= max_step_) {
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
  double max_step_;
  Vector7d previous_ = Vector7d::Zero();
  int last_ = -10;
};

}  // namespace pcl_ls3d
