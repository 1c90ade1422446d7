#pragma once
/// \file terrain.h
/// \brief A smooth analytic terrain with relief in every horizontal direction.

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace pcl_ls3d {
namespace synth {

/// \brief h(x, y) = Σ_k a_k sin(2π (d_k · (x, y)) / λ_k + ψ_k), a sum of seeded plane waves.
///
/// Eight waves: six with directions spread evenly over 180° (jittered ±15°) and wavelengths in
/// [0.6, 1.6]·wavelength, two long ones (3·wavelength) that add broad undulation. Because the
/// directions cover the half circle, the surface has slope in every horizontal direction and a
/// horizontal shift is determinable by surface matching; the wavelengths are incommensurate, so
/// there is no short period. Amplitudes are scaled so that the RMS height is relief/4: ±2 RMS
/// spans `relief`, which is about the peak-to-peak height over an area a few wavelengths wide
/// (seed 1, defaults, 420 m × 300 m: range 9.2 m, RMS slope 0.12, max slope 0.31).
class Terrain
{
public:
  /// \param seed       selects directions, wavelengths, phases and amplitudes
  /// \param relief     nominal peak-to-peak height, 4 × RMS height [m]
  /// \param wavelength typical horizontal wavelength [m]
  explicit Terrain(std::uint32_t seed, double relief = 10.0, double wavelength = 60.0);

  /// Height at (x, y).
  double
  height(double x, double y) const;

  /// (∂h/∂x, ∂h/∂y).
  Eigen::Vector2d
  gradient(double x, double y) const;

  /// Upward unit normal (−h_x, −h_y, 1)/‖·‖.
  Eigen::Vector3d
  normal(double x, double y) const;

  std::uint32_t
  seed() const
  {
    return seed_;
  }
  double
  relief() const
  {
    return relief_;
  }
  double
  wavelength() const
  {
    return wavelength_;
  }

private:
  struct Wave
  {
    double kx, ky;     ///< 2π d / λ [rad/m]
    double amplitude;  ///< [m]
    double phase;      ///< [rad]
  };
  std::vector<Wave> waves_;
  std::uint32_t seed_;
  double relief_;
  double wavelength_;
};

}  // namespace synth
}  // namespace pcl_ls3d
