#include <pcl_ls3d/synth/random.h>
#include <pcl_ls3d/synth/terrain.h>

#include <cmath>

namespace pcl_ls3d {
namespace synth {

Terrain::Terrain(std::uint32_t seed, double relief, double wavelength)
    : seed_(seed), relief_(relief), wavelength_(wavelength)
{
  Random rng(seed, 0x7e44a1u, 0u);
  constexpr int kShort = 6;
  constexpr double kPi = 3.14159265358979323846;
  double sum_sq = 0.0;
  for (int k = 0; k < kShort + 2; ++k) {
    double direction, lambda;
    if (k < kShort) {
      direction = (k + rng.uniform(-0.5, 0.5)) * kPi / kShort;  // ±15° about k·30°
      lambda = wavelength * rng.uniform(0.6, 1.6);
    } else {
      direction = rng.uniform(0.0, kPi);
      lambda = 3.0 * wavelength * rng.uniform(0.9, 1.1);
    }
    // Longer waves get larger amplitudes, as in real terrain; slope stays bounded.
    const double amplitude = lambda * rng.uniform(0.7, 1.3);
    const double w = 2.0 * kPi / lambda;
    waves_.push_back(
        {w * std::cos(direction), w * std::sin(direction), amplitude, rng.uniform(0.0, 2.0 * kPi)});
    sum_sq += amplitude * amplitude;
  }
  // RMS height sqrt(Σa²/2) = relief/4, so ±2 RMS spans `relief`.
  const double scale = sum_sq > 0.0 ? 0.25 * relief / std::sqrt(0.5 * sum_sq) : 0.0;
  for (auto& wave : waves_)
    wave.amplitude *= scale;
}

double
Terrain::height(double x, double y) const
{
  double h = 0.0;
  for (const auto& w : waves_)
    h += w.amplitude * std::sin(w.kx * x + w.ky * y + w.phase);
  return h;
}

Eigen::Vector2d
Terrain::gradient(double x, double y) const
{
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  for (const auto& w : waves_) {
    const double c = w.amplitude * std::cos(w.kx * x + w.ky * y + w.phase);
    g += c * Eigen::Vector2d(w.kx, w.ky);
  }
  return g;
}

Eigen::Vector3d
Terrain::normal(double x, double y) const
{
  const Eigen::Vector2d g = gradient(x, y);
  return Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
}

}  // namespace synth
}  // namespace pcl_ls3d
