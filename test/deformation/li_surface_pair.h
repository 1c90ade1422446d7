#pragma once
// Shared fixture of the deformation and robust-matching tests: a generated Li surface pair,
// the mate (epoch) to be matched onto the reference with the LZD rule (Li et al.'s LHD), and
// the worst grid-node error of a transformation against the truth.
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/rules/conjugate_rule.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/search/kdtree.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace li_test {

/// Li's surface with `percent` of the nodes raised by N(c σ, σ) at `position`; every other
/// setting the generator's default (50 × 50 nodes, Table 4's transform).
inline pcl_ls3d::synth::LiSurface
liSurface(double percent, double c, pcl_ls3d::synth::DeformationPosition position, std::uint32_t seed = 1)
{
  pcl_ls3d::synth::LiSurfaceSettings s;
  s.deformation_percent = percent;
  s.deformation_c = c;
  s.position = position;
  s.seed = seed;
  return pcl_ls3d::synth::makeLiSurface(s);
}

/// A small, nearly flat surface (30 × 30 nodes at 1.2 m, relief 0.5 m over a 40 m wavelength,
/// noise 3 cm) with its middle 38 % raised by N(8σ, σ), identity truth: the surface fixes heights
/// and tilts, barely the position in plan. The all-points least-squares fit slides off it.
inline pcl_ls3d::synth::LiSurface
gentleTerrain(double relief = 0.5)
{
  pcl_ls3d::synth::LiSurfaceSettings s;
  s.grid_size = 30;
  s.spacing = 1.2;
  s.relief = relief;
  s.wavelength = 40.0;
  s.noise_sigma = 0.03;
  s.deformation_percent = 38.0;
  s.deformation_c = 8.0;
  s.position = pcl_ls3d::synth::DeformationPosition::MIDDLE;
  s.truth = pcl_ls3d::SimilarityTransform();
  return pcl_ls3d::synth::makeLiSurface(s);
}

struct LiSurfacePair
{
  explicit LiSurfacePair(pcl_ls3d::synth::LiSurface generated) : li(std::move(generated))
  {
    for (std::size_t i = 0; i < li.mate->size(); ++i) {
      points.push_back((*li.mate)[i].getVector3fMap().cast<double>());
      indices.push_back(static_cast<int>(i));
    }
    tree.reset(new pcl::search::KdTree<pcl_ls3d::PointLiDAR>);
    tree->setInputCloud(li.reference);
    surface = std::make_shared<pcl_ls3d::PclTargetSurface<pcl_ls3d::PointLiDAR>>(li.reference, tree);
    rule = pcl_ls3d::makeConjugateRule(pcl_ls3d::ConjugateRuleType::LZD);
    std::string why;
    rule->prepare(*surface, &why);
  }

  /// Worst displacement of a grid node under T against the truth, in units of the generator's
  /// noise σ (the default LiSurfaceSettings::noise_sigma, which these tests use).
  double
  errorSigma(const Eigen::Matrix4d& T) const
  {
    Eigen::Matrix3Xd pts(3, static_cast<Eigen::Index>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i)
      pts.col(static_cast<Eigen::Index>(i)) = points[i];
    return pcl_ls3d::evaluation::computeTransformError(T, li.truth.matrix(), pts).max /
           pcl_ls3d::synth::LiSurfaceSettings().noise_sigma;
  }

  pcl_ls3d::synth::LiSurface li;
  std::vector<Eigen::Vector3d> points;  ///< the mate's nodes, epoch coordinates
  std::vector<int> indices;             ///< 0 … n − 1
  pcl::search::KdTree<pcl_ls3d::PointLiDAR>::Ptr tree;
  std::shared_ptr<pcl_ls3d::PclTargetSurface<pcl_ls3d::PointLiDAR>> surface;
  pcl_ls3d::ConjugateRule::Ptr rule;
};

}  // namespace li_test
