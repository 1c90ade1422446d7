#pragma once
/// \file random.h
/// \brief The generators' random numbers: std::mt19937 with distributions written out here.
///
/// std::normal_distribution and std::uniform_real_distribution are implementation-defined, so
/// the same seed could give different clouds with libstdc++ and libc++. mt19937 and
/// std::seed_seq are fully specified by the standard; the uniform (53-bit) and normal (Marsaglia
/// polar) draws below are ours, so a seed gives bit-identical numbers with every library.

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <random>

namespace pcl_ls3d {
namespace synth {

/// \brief A seeded stream of uniform and normal draws. Streams for parallel blocks are keyed by
///        (seed, stream, block), so results do not depend on the number of threads.
class Random
{
public:
  explicit Random(std::uint32_t seed) : engine_(seed)
  {}

  /// Independent stream for (seed, stream id, block id), via std::seed_seq.
  Random(std::uint32_t seed, std::uint32_t stream, std::uint32_t block)
  {
    std::seed_seq seq{seed, stream, block, 0x5eedu};
    engine_.seed(seq);
  }

  /// Uniform in [0, 1) with 53 random bits.
  double
  uniform()
  {
    const std::uint64_t a = engine_() >> 5;  // 27 bits
    const std::uint64_t b = engine_() >> 6;  // 26 bits
    return (static_cast<double>(a) * 67108864.0 + static_cast<double>(b)) * (1.0 / 9007199254740992.0);
  }

  /// Uniform in [lo, hi).
  double
  uniform(double lo, double hi)
  {
    return lo + (hi - lo) * uniform();
  }

  /// Uniform integer in [0, n); n > 0.
  std::uint32_t
  index(std::uint32_t n)
  {
    return static_cast<std::uint32_t>(uniform() * n) % n;
  }

  /// Standard normal N(0, 1) (Marsaglia polar method).
  double
  normal()
  {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

  /// N(mean, sigma).
  double
  normal(double mean, double sigma)
  {
    return mean + sigma * normal();
  }

  /// Isotropic 3D noise, each axis N(0, sigma).
  Eigen::Vector3d
  normal3(double sigma)
  {
    const double a = normal(), b = normal(), c = normal();
    return sigma * Eigen::Vector3d(a, b, c);
  }

  std::mt19937&
  engine()
  {
    return engine_;
  }

private:
  std::mt19937 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace synth
}  // namespace pcl_ls3d
