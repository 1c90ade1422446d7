#include <pcl_ls3d/adjustment/parameter_block.h>

#include <cmath>
#include <limits>

namespace pcl_ls3d {

bool
parseParameterModel(const std::string& text, ParameterModel& model)
{
  if (text == "7")
    model = ParameterModel::SIMILARITY_7;
  else if (text == "6")
    model = ParameterModel::RIGID_6;
  else if (text == "3")
    model = ParameterModel::TRANSLATION_3;
  else if (text == "z" || text == "1")
    model = ParameterModel::HEIGHT_1;
  else
    return false;
  return true;
}

std::string
parameterModelName(ParameterModel model)
{
  switch (model) {
  case ParameterModel::SIMILARITY_7:
    return "7";
  case ParameterModel::RIGID_6:
    return "6";
  case ParameterModel::TRANSLATION_3:
    return "3";
  case ParameterModel::HEIGHT_1:
    return "z";
  }
  return "?";
}

Vector7d
parameterModelWeights(ParameterModel model)
{
  // Which parameters each preset estimates, in the order tx, ty, tz, φ, ω, κ, m.
  static const bool free_params[4][7] = {{true, true, true, true, true, true, true},
                                         {true, true, true, true, true, true, false},
                                         {true, true, true, false, false, false, false},
                                         {false, false, true, false, false, false, false}};
  const int row = static_cast<int>(model);
  Vector7d weights;
  for (int i = 0; i < 7; ++i)
    weights[i] = free_params[row][i] ? 0.0 : std::numeric_limits<double>::infinity();
  return weights;
}

int
freeParameterCount(const Vector7d& apriori_weights)
{
  int n = 0;
  for (int i = 0; i < 7; ++i)
    n += !std::isinf(apriori_weights[i]);
  return n;
}

ParameterBlock
ParameterBlock::fixedIdentity(const Eigen::Vector3d& origin)
{
  ParameterBlock block;
  block.input_origin = block.output_origin = origin;
  block.apriori_weights.setConstant(std::numeric_limits<double>::infinity());
  return block;
}

bool
ParameterBlock::isFixed(int index) const
{
  return index >= 0 && index < 7 && std::isinf(apriori_weights[index]);
}

bool
ParameterBlock::allFixed() const
{
  for (int i = 0; i < 7; ++i)
    if (!isFixed(i))
      return false;
  return true;
}

bool
ParameterBlock::isFixedIdentity() const
{
  return allFixed() && values == identityParameters() && input_origin == output_origin;
}

Eigen::Matrix4d
ParameterBlock::matrix() const
{
  return localToGlobal(SimilarityTransform(values).matrix(), input_origin, output_origin);
}

BlockLinearization::BlockLinearization(const ParameterBlock& block)
    : lin_(SimilarityTransform(block.values)), input_origin_(block.input_origin),
      output_origin_(block.output_origin), rotation_(SimilarityTransform(block.values).rotation()),
      scale_(block.values[SCALE]), identity_(block.isFixedIdentity())
{}

Eigen::Vector3d
BlockLinearization::toInput(const Eigen::Vector3d& x_out) const
{
  if (identity_)
    return x_out;
  const Eigen::Vector3d t = lin_.apply(Eigen::Vector3d::Zero());
  return input_origin_ + rotation_.transpose() * (x_out - output_origin_ - t) / scale_;
}

}  // namespace pcl_ls3d
