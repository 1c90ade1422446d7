// benchmark_deformation_li: Li et al. (2001) Tables 2-5 analogues on the generator's Li surface.
#include <pcl_ls3d/estimators/robust_matching.h>
#include <pcl_ls3d/evaluation/transform_error.h>
#include <pcl_ls3d/registration/pcl_target_surface.h>
#include <pcl_ls3d/synth/li_surface.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/console/time.h>
#include <pcl/search/kdtree.h>

#include <cstdio>

using namespace pcl_ls3d;

int
main(int argc, char** argv)
{
  synth::LiSurfaceSettings ls;
  double percent = 9, c = 10;
  int seed = 1;
  std::string pos = "upper_left", methods = "ls,m,md,lms,mm";
  bool table4 = pcl::console::find_switch(argc, argv, "-table4");
  pcl::console::parse_argument(argc, argv, "-percent", percent);
  pcl::console::parse_argument(argc, argv, "-c", c);
  pcl::console::parse_argument(argc, argv, "-seed", seed);
  pcl::console::parse_argument(argc, argv, "-position", pos);
  pcl::console::parse_argument(argc, argv, "-methods", methods);
  pcl::console::parse_argument(argc, argv, "-wavelength", ls.wavelength);
  ls.deformation_percent = percent;
  ls.deformation_c = c;
  ls.seed = static_cast<std::uint32_t>(seed);
  synth::parseDeformationPosition(pos, ls.position);
  if (table4) {
    Vector7d p;
    const double a = 5.0 * M_PI / 180.0;
    p << 500, 500, 500, a, a, a, 1;
    ls.truth = SimilarityTransform(p);
  }
  const synth::LiSurface li = synth::makeLiSurface(ls);
  std::vector<Eigen::Vector3d> pts;
  std::vector<int> idx;
  Eigen::Matrix3Xd eval(3, li.mate->size());
  for (std::size_t i = 0; i < li.mate->size(); ++i) {
    pts.push_back((*li.mate)[i].getVector3fMap().cast<double>());
    idx.push_back(static_cast<int>(i));
    eval.col(static_cast<Eigen::Index>(i)) = pts.back();
  }
  pcl::search::KdTree<PointLiDAR>::Ptr tree(new pcl::search::KdTree<PointLiDAR>);
  tree->setInputCloud(li.reference);
  PclTargetSurface<PointLiDAR> surface(li.reference, tree);
  const ConjugateRule::Ptr rule = makeConjugateRule(ConjugateRuleType::LZD);
  std::string why;
  rule->prepare(surface, &why);
  std::stringstream ss(methods);
  std::string m;
  while (std::getline(ss, m, ',')) {
    RobustMatchingSettings s;
    parseRobustMethod(m, s.method);
    pcl::console::TicToc tt;
    tt.tic();
    const RobustMatchingReport r = robustMatching(pts, idx, surface, *rule, s, Eigen::Matrix4d::Identity());
    const double ms = tt.toc();
    const auto e = evaluation::computeTransformError(r.adjustment.transformation, li.truth.matrix(), eval);
    const auto e0 = evaluation::computeTransformError(r.start.transformation, li.truth.matrix(), eval);
    {
      double sd = 0, sc = 0; int nd = 0, nc = 0;
      const auto& A = r.adjustment;
      for (std::size_t j = 0; j < A.residuals.size(); ++j) {
        if (li.deformed[static_cast<std::size_t>(A.observation_source_index[j])]) { sd += A.residuals[j]; ++nd; }
        else { sc += A.residuals[j]; ++nc; }
      }
      std::printf("   obs %zu deformed %d mean %.1f clean %d mean %.1f\n", A.residuals.size(), nd, sd / nd, nc, sc / nc);
    }
    std::printf("%-4s max %8.2f sigma (mean %6.2f)  start max %8.2f  scale %.2f hb %.2f  %s  %.0f ms\n", m.c_str(),
                e.max / ls.noise_sigma, e.mean / ls.noise_sigma, e0.max / ls.noise_sigma, r.scale,
                r.high_breakdown_scale, r.brief().c_str(), ms);
  }
  return 0;
}
