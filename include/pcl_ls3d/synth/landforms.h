#pragma once
/// \file landforms.h
/// \brief The ground of a mountainous scene (Zuo et al. 2012, Henan): a Terrain cut into
///        hillside terraces (flat treads joined by steep risers) and crossed by straight
///        scarps (a step of several metres over a few metres of steep face).
///
/// Terraces: with step S and riser share w, h' = S (k + s((f − 1 + w) / w)), k = ⌊h/S⌋,
/// f = h/S − k, s the clamped smoothstep: a tread is flat at kS for (1 − w) of each step of the
/// underlying height and the riser climbs to (k + 1)S over the remaining w, continuously.
/// Scarp k: a line through p_k with normal n_k; the ground on its positive side is raised by
/// H_k s(n_k·(x − p_k) / width + ½). Both keep the surface continuous (a steep face, no jump).

#include <pcl_ls3d/synth/terrain.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace synth {

/// \brief Terraces and scarps on top of a Terrain (all off by default).
struct LandformSettings
{
  double terrace_step = 0.0;                               ///< height of one terrace [m]; 0 = no terraces
  double terrace_riser = 0.3;                              ///< share of each step taken by the riser, (0, 1]
  int scarps = 0;                                          ///< straight scarps through the region
  double min_scarp_height = 4.0, max_scarp_height = 10.0;  ///< [m]
  double scarp_width = 3.0;                                ///< horizontal width of a scarp's face [m]

  bool
  isValid(std::string* why = nullptr) const;
};

/// \brief One straight scarp.
struct Scarp
{
  Eigen::Vector2d point = Eigen::Vector2d::Zero();    ///< on the middle of the face
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  ///< towards the raised side
  double height = 0.0;                                ///< [m]
};

/// \brief The ground: terrain, terraces, scarps.
class Ground
{
public:
  /// Scarps are drawn from `seed` through `region` (directions uniform, points inside).
  Ground(Terrain terrain, const LandformSettings& settings, const Eigen::AlignedBox2d& region,
         std::uint32_t seed);

  /// Ground height at (x, y).
  double
  height(double x, double y) const;

  const Terrain&
  terrain() const
  {
    return terrain_;
  }
  const std::vector<Scarp>&
  scarps() const
  {
    return scarps_;
  }

private:
  Terrain terrain_;
  LandformSettings settings_;
  std::vector<Scarp> scarps_;
};

}  // namespace synth
}  // namespace pcl_ls3d
