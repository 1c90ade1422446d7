// End-to-end quality on a small generated scene (synth::makeScene, 60 m × 60 m, known ASPRS
// labels): IMRG must recover ground, building and vegetation with a per-class F1 above a bound,
// and the evaluation must be consistent with an independent per-point count.
#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_runner.h>
#include <pcl_ls3d/synth/scene.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <map>

namespace ev = pcl_ls3d::evaluation;

namespace {
struct SmallScene
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
  std::vector<int> labels;
};

SmallScene
makeSmall(std::uint32_t seed)
{
  pcl_ls3d::synth::SceneSettings s;
  s.seed = seed;
  s.size_x = s.size_y = 60.0;
  s.power_line = false;  // wires need a longer span than 60 m to be meaningful
  const auto scene = pcl_ls3d::synth::makeScene(s);
  SmallScene out;
  for (const auto& p : scene.cloud->points) {
    out.cloud->push_back(pcl::PointXYZ(p.x, p.y, p.z));
    out.labels.push_back(p.classification);
  }
  return out;
}
}  // namespace

TEST(SegmentationQuality, ImrgOnSmallGeneratedScene)
{
  const SmallScene scene = makeSmall(5);
  ASSERT_GT(scene.cloud->size(), 10000u);
  ev::SegmentationRunSettings settings;  // IMRG, all thresholds adaptive
  ev::SegmentationRun run;
  std::string error;
  ASSERT_TRUE(ev::runSegmentation(scene.cloud, settings, run, error)) << error;
  EXPECT_EQ(run.linear + run.planar + run.volumetric + run.invalid, scene.cloud->size());
  EXPECT_GE(run.segments_before_merge, run.segments.size());

  ev::SegmentationEvaluation e;
  ASSERT_TRUE(ev::evaluateSegmentation(run.segments, scene.labels, {}, e, error)) << error;
  // Bound 0.90: the benchmark measures 0.99+ on 100 m scenes (docs/BENCHMARKS.md); 0.90 leaves
  // room for seed-to-seed variation of a 60 m scene while still failing on a class mix-up.
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_GE(e.classes[c].f1, 0.90) << e.classes[c].name;
    std::printf("  %s F1 %.4f (P %.4f R %.4f)\n", e.classes[c].name.c_str(), e.classes[c].f1,
                e.classes[c].precision, e.classes[c].recall);
  }

  // Independent check of the ground F1: recount TP/FP/FN from per-point labels.
  const auto seg_of = ev::labelsFromSegments(run.segments, scene.cloud->size());
  std::map<std::uint32_t, std::map<int, std::size_t>> votes;
  for (std::size_t i = 0; i < seg_of.size(); ++i)
    if (scene.labels[i] > 1 && seg_of[i] > 0)
      ++votes[seg_of[i]][scene.labels[i] >= 3 && scene.labels[i] <= 5 ? 3 : scene.labels[i]];
  std::size_t tp = 0, fp = 0, fn = 0;
  for (std::size_t i = 0; i < seg_of.size(); ++i) {
    if (scene.labels[i] <= 1)
      continue;
    int predicted = -1;
    if (seg_of[i] > 0) {
      std::size_t best = 0;
      for (const auto& kv : votes[seg_of[i]])  // ascending code: 2 (ground) wins ties
        if (kv.second > best) {
          best = kv.second;
          predicted = kv.first;
        }
    }
    const bool ref_ground = scene.labels[i] == 2, pred_ground = predicted == 2;
    tp += ref_ground && pred_ground;
    fp += !ref_ground && pred_ground;
    fn += ref_ground && !pred_ground;
  }
  EXPECT_EQ(e.classes[0].tp, tp);
  EXPECT_EQ(e.classes[0].fp, fp);
  EXPECT_EQ(e.classes[0].fn, fn);
}
