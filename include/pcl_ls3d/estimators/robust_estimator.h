#pragma once
/// \file robust_estimator.h
/// \brief The catalogue of weight-function estimators (interface in robust_estimator_base.h, one
///        header per estimator) and the factory and name parser the tools use.
///
/// | estimator | weight w(u), u = v / σ̂ | σ̂ (default) | constant |
/// |---|---|---|---|
/// | LeastSquaresEstimator | 1 | — | — |
/// | ZuoEstimator (Zuo 2012 eq. 15) | 0 if \|v\| > K σ̂0 else 1 | σ̂0 of the last solve | K = 6 |
/// | HuberEstimator | min(1, k/\|u\|) | 1.4826 MAD | k = 1.345 (95 %) |
/// | TukeyEstimator (Li "M", eqs. 6–8) | (1 − u²/c²)² inside c | 1.4826 MAD (eq. 7) | c = 4.685 (95 %) |
/// | MdEstimator (Li "M-D", eq. 10) | Tukey on v / (σ̂ √r_i) | σ̂0 of the last solve | c = 4.685 |
///
/// High-breakdown estimators (LMS, LTS, MM) are not weight functions: see
/// sample_consensus/sac_model_surface_matching.h and estimators/robust_matching.h.

#include <pcl_ls3d/estimators/huber_estimator.h>
#include <pcl_ls3d/estimators/least_squares_estimator.h>
#include <pcl_ls3d/estimators/md_estimator.h>
#include <pcl_ls3d/estimators/robust_estimator_base.h>
#include <pcl_ls3d/estimators/robust_scale.h>
#include <pcl_ls3d/estimators/tukey_estimator.h>
#include <pcl_ls3d/estimators/zuo_estimator.h>

#include <limits>
#include <string>

namespace pcl_ls3d {

/// The weight-function estimators shipped with the library.
enum class RobustEstimatorType
{
  LEAST_SQUARES,  ///< w = 1
  ZUO,            ///< Zuo et al. 2012, eq. 15: 0/1 weight at K σ0 (default K = 6)
  HUBER,          ///< Huber, k = 1.345 (95 % efficiency), MAD scale
  TUKEY,          ///< Tukey biweight on 1.4826 MAD, c = 4.685 (95 % efficiency); Li's "M"
  MD              ///< Li's M-D / GM: Tukey on Baarda's normalised residual v / (σ0 √r_i)
};

/// Creates one of the shipped estimators; a finite `constant` replaces its default tuning
/// constant (K, k or c, in σ units).
RobustEstimator::Ptr
makeRobustEstimator(RobustEstimatorType type, double constant = std::numeric_limits<double>::quiet_NaN());

/// \brief One of the shipped estimators with its tuning constant: a plain value that settings can
///        hold, copy and write to a file (the estimator object itself is made when it is used).
struct RobustEstimatorChoice
{
  RobustEstimatorType type = RobustEstimatorType::ZUO;
  double constant = std::numeric_limits<double>::quiet_NaN();  ///< NaN: the type's default
};

/// The estimator a choice names.
RobustEstimator::Ptr
makeRobustEstimator(const RobustEstimatorChoice& choice);

/// Parses "ls", "zuo", "huber", "tukey" (or "m", Li's name), "md" (or "m-d", "gm"),
/// case-insensitive, optionally with a tuning constant after a colon ("zuo:7", "huber:1.5").
/// False with the reason when the text is not one (\a choice untouched).
bool
parseRobustEstimatorChoice(const std::string& text, RobustEstimatorChoice& choice,
                           std::string* why = nullptr);

/// "zuo", "huber:1.5": the text parseRobustEstimatorChoice() reads back to the same choice.
std::string
toString(const RobustEstimatorChoice& choice);

/// parseRobustEstimatorChoice() and makeRobustEstimator() in one: null, with the reason, when the
/// text names no estimator.
RobustEstimator::Ptr
parseRobustEstimator(const std::string& text, std::string* why = nullptr);

}  // namespace pcl_ls3d
