#pragma once
/// \file parameter_block.h
/// \brief Stage 1 of the engine: the parameters of one rigid body (a source cloud, a target
///        cloud, a flight strip) and the local frame they act in. A pair adjustment has two
///        blocks (the target's fixed at identity), a strip block adjustment one per strip.
///
/// A block maps a point x of its body (input coordinates) to the common output frame as
///   x_out = o_out + t + m R(φ, ω, κ) (x − o_in)          (Zuo et al. 2012, eq. 2, reduced)
/// Reducing both sides to local origins near the data keeps rotations and translations from
/// being almost perfectly correlated on georeferenced coordinates.

#include <pcl_ls3d/adjustment/similarity_jacobian.h>

#include <array>
#include <string>

namespace pcl_ls3d {

/// \brief Which of the 7 similarity parameters (tx, ty, tz, φ, ω, κ, m) are estimated.
enum class ParameterModel
{
  SIMILARITY_7,   ///< all seven free
  RIGID_6,        ///< m fixed (Zuo's 6-parameter case; LHD = LZD rule + RIGID_6)
  TRANSLATION_3,  ///< tx, ty, tz free; rotations and scale fixed
  HEIGHT_1        ///< only tz free (classic strip height offset)
};

/// "7", "6", "3", "z" (or "1") → model, the one spelling of -params; false when unknown.
bool
parseParameterModel(const std::string& text, ParameterModel& model);
/// "7", "6", "3", "z".
std::string
parameterModelName(ParameterModel model);

/// The a-priori weights of a preset: 0 for the model's parameters, +inf for the others.
Vector7d
parameterModelWeights(ParameterModel model);

/// How many of the 7 parameters the a-priori weights leave to be estimated (weight not +inf:
/// free or softly constrained).
int
freeParameterCount(const Vector7d& apriori_weights);

/// The identity similarity (t = 0, angles 0, m = 1) as a parameter vector.
inline Vector7d
identityParameters()
{
  return (Vector7d() << 0, 0, 0, 0, 0, 0, 1).finished();
}

/// \brief One body's similarity in its local frame, with its a-priori observations (eq. 9):
///        V_e = X − L_e with weight P_e per parameter, 0 = free, +inf = fixed, else soft.
struct ParameterBlock
{
  Eigen::Vector3d input_origin = Eigen::Vector3d::Zero();   ///< o_in (body coordinates)
  Eigen::Vector3d output_origin = Eigen::Vector3d::Zero();  ///< o_out (common frame)
  Vector7d values = identityParameters();                   ///< X
  Vector7d apriori_values = identityParameters();           ///< L_e
  Vector7d apriori_weights = Vector7d::Zero();              ///< P_e

  /// A block held at the identity about `origin` (e.g. the target of a pair).
  static ParameterBlock
  fixedIdentity(const Eigen::Vector3d& origin);

  bool
  isFixed(int index) const;
  /// True when every parameter has infinite weight.
  bool
  allFixed() const;
  /// True when the block is fixed at the identity with o_in = o_out (maps every point onto itself).
  bool
  isFixedIdentity() const;

  /// The 4×4 matrix mapping body coordinates to the common frame.
  Eigen::Matrix4d
  matrix() const;
};

/// \brief A block linearised at its current values: maps points, inverts the map, and gives the
///        design-matrix rows of its parameters. Built once per iteration.
class BlockLinearization
{
public:
  explicit BlockLinearization(const ParameterBlock& block);

  /// x_out for a point given reduced to the block's input origin (x − o_in).
  Eigen::Vector3d
  toOutput(const Eigen::Vector3d& reduced) const
  {
    return identity_ ? input_origin_ + reduced : output_origin_ + lin_.apply(reduced);
  }
  /// The body coordinates of a point of the common frame (exactly x_out for a fixed identity).
  Eigen::Vector3d
  toInput(const Eigen::Vector3d& x_out) const;
  /// Rotates a direction given in body coordinates into the common frame.
  Eigen::Vector3d
  directionToOutput(const Eigen::Vector3d& u) const
  {
    return identity_ ? u : rotation_ * u;
  }
  /// Scale m of the block (distances in body coordinates times m are distances in the common frame).
  double
  scale() const
  {
    return scale_;
  }
  /// a = uᵀ ∂x_out/∂X for a point given reduced to the input origin.
  RowVector7d
  designRow(const Eigen::Vector3d& u, const Eigen::Vector3d& reduced) const
  {
    return lin_.designRow(u, reduced);
  }
  const Eigen::Vector3d&
  inputOrigin() const
  {
    return input_origin_;
  }
  const SimilarityLinearization&
  similarity() const
  {
    return lin_;
  }
  /// True for a fixed identity block: points are used as they are (no arithmetic, no rounding).
  bool
  identity() const
  {
    return identity_;
  }

private:
  SimilarityLinearization lin_;
  Eigen::Vector3d input_origin_, output_origin_;
  Eigen::Matrix3d rotation_;
  double scale_ = 1.0;
  bool identity_ = false;
};

}  // namespace pcl_ls3d
