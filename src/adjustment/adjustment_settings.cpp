#include <pcl_ls3d/adjustment/adjustment_settings.h>

#include <pcl_ls3d/common/similarity_transform.h>

#include <cmath>

namespace pcl_ls3d {

void
AdjustmentSettings::fixParameter(int index, bool fixed)
{
  if (index < 0 || index > 6)
    return;
  apriori_weights[index] = fixed ? std::numeric_limits<double>::infinity() : 0.0;
}

bool
AdjustmentSettings::isFixed(int index) const
{
  return index >= 0 && index < 7 && std::isinf(apriori_weights[index]);
}

void
AdjustmentSettings::setParameterModel(ParameterModel model)
{
  // Soft weights are lost: the preset frees its parameters and fixes the rest.
  apriori_weights = parameterModelWeights(model);
}

AdjustmentSettings
AdjustmentSettings::similarity7()
{
  AdjustmentSettings s;
  s.setParameterModel(ParameterModel::SIMILARITY_7);
  return s;
}

AdjustmentSettings
AdjustmentSettings::rigid6()
{
  AdjustmentSettings s;
  s.setParameterModel(ParameterModel::RIGID_6);
  return s;
}

AdjustmentSettings
AdjustmentSettings::translationOnly()
{
  AdjustmentSettings s;
  s.setParameterModel(ParameterModel::TRANSLATION_3);
  return s;
}

AdjustmentSettings
AdjustmentSettings::heightOnly()
{
  AdjustmentSettings s;
  s.setParameterModel(ParameterModel::HEIGHT_1);
  return s;
}

bool
AdjustmentSettings::isValid(std::string* why) const
{
  auto fail = [why](const std::string& text) {
    if (why)
      *why = text;
    return false;
  };
  bool any_free = false;
  for (int i = 0; i < 7; ++i) {
    if (std::isnan(apriori_weights[i]) || apriori_weights[i] < 0.0)
      return fail("a-priori weight of " + similarityParameterNames()[static_cast<std::size_t>(i)] +
                  " must be >= 0 (0 free, inf fixed)");
    if (!std::isfinite(apriori_values[i]))
      return fail("a-priori value of " + similarityParameterNames()[static_cast<std::size_t>(i)] +
                  " is not finite");
    any_free = any_free || !std::isinf(apriori_weights[i]);
  }
  if (!any_free)
    return fail("every parameter is fixed: nothing to estimate");
  if (!apriori_from_guess && !(apriori_values[SCALE] > 0.0))
    return fail("a-priori scale m must be > 0");
  if (max_iterations < 1)
    return fail("max_iterations must be >= 1");
  if (!(angle_epsilon > 0.0) || !(translation_epsilon > 0.0) || !(scale_epsilon > 0.0))
    return fail("convergence epsilons must be > 0");
  if (!(max_correspondence_distance > 0.0))
    return fail("max_correspondence_distance must be > 0");
  if (!(source_thinning >= 0.0) || std::isinf(source_thinning))
    return fail("source_thinning must be >= 0 and finite");
  if (!(guess_uncertainty >= 0.0) || std::isinf(guess_uncertainty))
    return fail("guess_uncertainty must be >= 0 and finite");
  if (recheck_interval < 0)
    return fail("recheck_interval must be >= 0");
  if (!(precision_cell >= 0.0) || std::isinf(precision_cell))
    return fail("precision_cell must be >= 0 and finite");
  if (!(freeze_sigma_fraction >= 0.0) || std::isinf(freeze_sigma_fraction))
    return fail("freeze_sigma_fraction must be >= 0 and finite");
  if (min_observations < 1)
    return fail("min_observations must be >= 1");
  if (!(max_scale_deviation > 0.0) || !(max_sigma0_ratio > 0.0) || !(max_median_gradient >= 1.0) ||
      !(max_scale_growth >= 1.0))
    return fail(
        "max_scale_deviation, max_sigma0_ratio must be > 0, max_median_gradient and max_scale_growth >= 1 "
        "(+inf switches a test off)");
  if (!(min_coverage >= 0.0 && min_coverage <= 1.0) ||
      !(max_rejected_fraction >= 0.0 && max_rejected_fraction <= 1.0) ||
      !(min_observations_kept >= 0.0 && min_observations_kept <= 1.0))
    return fail("min_coverage, max_rejected_fraction and min_observations_kept must be in [0, 1]");
  if (!(min_movement_significance >= 0.0) || std::isinf(min_movement_significance) ||
      !(max_position_sigma_ratio > 0.0))
    return fail("min_movement_significance must be >= 0 and finite (0 switches the test off), "
                "max_position_sigma_ratio > 0 (+inf switches it off)");
  if (!(held_out_z > 0.0) || !(held_out_noise_factor >= 0.0) || std::isinf(held_out_noise_factor))
    return fail("held_out_z must be > 0 (+inf switches the test off), held_out_noise_factor >= 0 and finite");
  if (!(determinability_threshold > 0.0) || determinability_threshold >= 1.0)
    return fail("determinability_threshold must be in (0, 1)");
  return true;
}

ParameterBlock
sourceBlockFromGuess(const Eigen::Matrix4d& guess, const Eigen::Vector3d& reduction_origin,
                     const AdjustmentSettings& settings)
{
  ParameterBlock block;
  block.input_origin = reduction_origin;
  block.output_origin = (guess * reduction_origin.homogeneous()).head<3>();
  block.values =
      SimilarityTransform::fromMatrix(globalToLocal(guess, block.input_origin, block.output_origin)).vector();
  block.values.head<3>().setZero();  // o_t = guess(o_s) by construction
  block.apriori_values = settings.apriori_from_guess ? block.values : settings.apriori_values;
  block.apriori_weights = settings.apriori_weights;
  for (int i = 0; i < 7; ++i)
    if (settings.isFixed(i))
      block.values[i] = block.apriori_values[i];
  return block;
}

}  // namespace pcl_ls3d
