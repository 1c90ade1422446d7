// The object-based evaluation of Wang et al. 2021 §4.1 on hand-computed cases, reference objects
// from labels (connected components) and from ids, and the voxel baseline. Counts are integers:
// scores are compared exactly or to 1e-12.
#include <pcl_ls3d/evaluation/object_metrics.h>
#include <pcl_ls3d/evaluation/reference_objects.h>
#include <pcl_ls3d/evaluation/segmentation_report.h>
#include <pcl_ls3d/evaluation/voxel_baseline.h>

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace pcl_ls3d::evaluation;

namespace {
pcl::PointIndices
seg(std::vector<int> idx)
{
  pcl::PointIndices p;
  p.indices = std::move(idx);
  return p;
}

/// Objects given directly: object_of per point, groups per object.
ReferenceObjects
objects(std::vector<int> object_of, std::vector<int> group_of_object)
{
  ReferenceObjects r;
  r.object_of = std::move(object_of);
  r.group_of_object = std::move(group_of_object);
  r.size.assign(r.group_of_object.size(), 0);
  for (int o : r.object_of)
    if (o >= 0)
      ++r.size[static_cast<std::size_t>(o)];
  r.group_names = {"ground", "building"};
  return r;
}
}  // namespace

TEST(ObjectMetrics, PaperRulesByHand)
{
  // points 0..9 ground object 0; 10..15 building object 1; 16..19 building object 2;
  // point 20 unlabelled (excluded code).
  std::vector<int> of(21, 0);
  for (int i = 10; i < 16; ++i)
    of[static_cast<std::size_t>(i)] = 1;
  for (int i = 16; i < 20; ++i)
    of[static_cast<std::size_t>(i)] = 2;
  of[20] = ReferenceObjects::kUnlabelled;
  const ReferenceObjects ref = objects(of, {0, 1, 1});
  // S0 = 0..8 + 10 + 20: 9 of its 10 labelled points in object 0 -> valid for 0.
  // S1 = 11..13 + 16: 3 of 4 in object 1 -> valid for 1 (overlap 3 of 6: NOT > half).
  // S2 = 14, 15: valid for 1; with S1 object 1 holds 5 of 6 -> recognised.
  // S3 = 17, 18, 9: 2 of 3 in object 2 -> valid; 2 of 4 points is not > half -> object 2 not
  // recognised: its 4 points are FN, S3's stray ground point is not an FP.
  std::vector<int> s0{0, 1, 2, 3, 4, 5, 6, 7, 8, 10, 20};
  const std::vector<pcl::PointIndices> segments{seg(s0), seg({11, 12, 13, 16}), seg({14, 15}),
                                                seg({17, 18, 9})};
  ObjectEvaluation e;
  e.method = "m";
  std::string err;
  ASSERT_TRUE(evaluateObjects(segments, ref, {1}, e, err)) << err;
  EXPECT_EQ(e.method, "m");
  ASSERT_EQ(e.objects.size(), 3u);
  EXPECT_TRUE(e.objects[0].recognised);
  EXPECT_EQ(e.objects[0].valid_segments, 1u);
  EXPECT_NEAR(e.objects[0].largest_share, 0.9, 1e-12);
  EXPECT_TRUE(e.objects[1].recognised);
  EXPECT_EQ(e.objects[1].valid_segments, 2u);
  EXPECT_NEAR(e.objects[1].largest_share, 0.5, 1e-12);
  EXPECT_FALSE(e.objects[2].recognised);
  EXPECT_EQ(e.objects[2].valid_segments, 1u);

  const ObjectClassScores& g = e.classes[0];
  const ObjectClassScores& b = e.classes[1];
  // ground: TP 9, FP 1 (point 10 of S0), FN 1 (point 9 went to S3).
  EXPECT_EQ(g.tp, 9u);
  EXPECT_EQ(g.fp, 1u);
  EXPECT_EQ(g.fn, 1u);
  EXPECT_NEAR(g.f1, 0.9, 1e-12);
  // building: object 1 TP 5, FP 1 (point 16 in S1), FN 1 (point 10); object 2 FN 4.
  EXPECT_EQ(b.tp, 5u);
  EXPECT_EQ(b.fp, 1u);
  EXPECT_EQ(b.fn, 5u);
  EXPECT_NEAR(b.precision, 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(b.recall, 0.5, 1e-12);
  EXPECT_NEAR(b.f1, 2.0 * 5.0 / (2.0 * 5.0 + 1.0 + 5.0), 1e-12);
  EXPECT_EQ(b.objects, 2u);
  EXPECT_EQ(b.recognised, 1u);
  // Medians over objects of at least 1 point: valid segments {2, 1}, shares {0.5, 0.5}.
  EXPECT_DOUBLE_EQ(b.median_valid_segments, 1.5);
  EXPECT_DOUBLE_EQ(b.median_largest_share, 0.5);

  // Only objects of at least 5 points count in the medians: object 2 (4 points) drops out.
  ASSERT_TRUE(evaluateObjects(segments, ref, {5}, e, err));
  EXPECT_EQ(e.classes[1].large_objects, 1u);
  EXPECT_DOUBLE_EQ(e.classes[1].median_valid_segments, 2.0);

  // An index outside the reference is an error with a reason.
  EXPECT_FALSE(evaluateObjects({seg({0, 99})}, ref, {}, e, err));
  EXPECT_NE(err.find("99"), std::string::npos);
}

TEST(ObjectMetrics, FailedMethodIsATableRow)
{
  // Issue 11 defect 3: a method that failed is printed as a row with its reason; the columns
  // come from the first method that did not fail.
  std::vector<int> of(10, 0);
  const ReferenceObjects ref = objects(of, {0});
  ObjectEvaluation failed, good;
  failed.method = "pcl_rg";
  failed.failure = "no segment found";
  good.method = "imrg";
  std::string err;
  ASSERT_TRUE(evaluateObjects({seg({0, 1, 2, 3, 4, 5, 6, 7, 8, 9})}, ref, {1}, good, err));
  const std::string table = formatObjectTable({failed, good});
  EXPECT_NE(table.find("pcl_rg |"), std::string::npos) << table;
  EXPECT_NE(table.find("failed: no segment found"), std::string::npos) << table;
  EXPECT_NE(table.find("ground"), std::string::npos) << table;
  EXPECT_NE(table.find("100.0"), std::string::npos) << table;
  const std::string frag = formatFragmentationTable({failed, good}, 1);
  EXPECT_NE(frag.find("failed: no segment found"), std::string::npos) << frag;
}

TEST(SegmentationClasses, ExcludedCodesNamedByGroupsAreScored)
{
  // Issue 11 defect 6: a group naming code 1 takes it out of the excluded codes.
  const std::vector<int> excluded = defaultExcludedCodes();
  EXPECT_EQ(describeExcludedCodes(defaultClassGroups(), excluded), "codes 0/1 excluded");
  std::vector<ClassGroup> groups;
  std::string err;
  ASSERT_TRUE(parseClassGroups("ground=2,unclassified=1", groups, err)) << err;
  EXPECT_EQ(effectiveExcludedCodes(groups, excluded), std::vector<int>{0});
  EXPECT_EQ(describeExcludedCodes(groups, excluded), "code 0 excluded");
  ASSERT_TRUE(parseClassGroups("a=0,b=1", groups, err)) << err;
  EXPECT_EQ(describeExcludedCodes(groups, excluded), "no code excluded");
}

TEST(ObjectMetrics, OneSegmentForEverythingRecognisesOnlyTheLargestObject)
{
  std::vector<int> of(100, 0);
  for (int i = 60; i < 100; ++i)
    of[static_cast<std::size_t>(i)] = 1;
  const ReferenceObjects ref = objects(of, {0, 1});
  std::vector<int> all(100);
  for (int i = 0; i < 100; ++i)
    all[static_cast<std::size_t>(i)] = i;
  ObjectEvaluation e;
  std::string err;
  ASSERT_TRUE(evaluateObjects({seg(all)}, ref, {}, e, err));
  EXPECT_TRUE(e.objects[0].recognised);
  EXPECT_FALSE(e.objects[1].recognised);
  EXPECT_EQ(e.classes[0].fp, 40u);
  EXPECT_EQ(e.classes[1].fn, 40u);
  EXPECT_EQ(e.classes[1].tp + e.classes[1].fp, 0u);
  EXPECT_TRUE(std::isnan(e.classes[1].precision));
  EXPECT_DOUBLE_EQ(e.classes[1].f1, 0.0);
  // The tables show both classes and the fragmentation figures.
  const std::string t = formatObjectTable({e}) + formatFragmentationTable({e}, 200);
  EXPECT_NE(t.find("building P/R/F1"), std::string::npos);
  EXPECT_NE(t.find("0/1"), std::string::npos);
}

TEST(ReferenceObjects, ConnectedComponentsPerClassGroup)
{
  // Two building blocks 5 m apart, a ground strip touching both, one unclassified point.
  pcl::PointCloud<pcl::PointXYZ> c;
  std::vector<int> labels;
  for (float x = 0.f; x <= 3.f; x += 0.5f)
    for (float y = 0.f; y <= 3.f; y += 0.5f) {
      c.push_back(pcl::PointXYZ(x, y, 5.f));
      labels.push_back(6);
      c.push_back(pcl::PointXYZ(x + 8.f, y, 5.f));
      labels.push_back(6);
    }
  for (float x = -1.f; x <= 12.f; x += 0.5f) {
    c.push_back(pcl::PointXYZ(x, -0.5f, 4.6f));  // within 1 m of both roofs
    labels.push_back(2);
  }
  c.push_back(pcl::PointXYZ(20.f, 20.f, 0.f));
  labels.push_back(1);
  ReferenceObjectSettings s;
  s.radius = 1.0;
  ReferenceObjects r;
  std::string err;
  ASSERT_TRUE(referenceObjectsFromLabels(c, labels, s, r, err)) << err;
  ASSERT_EQ(r.objects(), 3u);  // 2 buildings + 1 ground strip; the class-1 point is unlabelled
  EXPECT_EQ(r.object_of.back(), ReferenceObjects::kUnlabelled);
  std::set<int> building_objects;
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] == 6)
      building_objects.insert(r.object_of[i]);
  EXPECT_EQ(building_objects.size(), 2u);
  for (int o : building_objects) {
    EXPECT_EQ(r.group_of_object[static_cast<std::size_t>(o)], 1);  // "building"
    EXPECT_EQ(r.size[static_cast<std::size_t>(o)], 49u);
  }
  // Automatic radius: at least 1 (the points here are 0.5 apart, 2.5 × 0.5 = 1.25).
  s.radius = -1.0;
  ASSERT_TRUE(referenceObjectsFromLabels(c, labels, s, r, err));
  EXPECT_NEAR(r.radius, 1.25, 1e-6);
  labels.pop_back();
  EXPECT_FALSE(referenceObjectsFromLabels(c, labels, s, r, err));
}

TEST(ReferenceObjects, BuildingIsOneObjectAcrossARoofStep)
{
  // A house whose annex roof lies 3 m below the main roof, 0.5 m beside it in plan, with no
  // wall points between: in 3-D the two roofs are 3 m apart, in plan 0.5 m. A tree of the same
  // shape stays two objects (vegetation is connected in 3-D: a shrub under a crown is not the
  // crown).
  pcl::PointCloud<pcl::PointXYZ> c;
  std::vector<int> labels;
  for (int code : {6, 5}) {
    const float y0 = code == 6 ? 0.f : 20.f;
    for (float x = 0.f; x <= 4.f; x += 0.5f)
      for (float y = y0; y <= y0 + 4.f; y += 0.5f) {
        c.push_back(pcl::PointXYZ(x, y, 8.f));
        labels.push_back(code);
        c.push_back(pcl::PointXYZ(x + 4.5f, y, 5.f));
        labels.push_back(code);
      }
  }
  ReferenceObjectSettings s;
  s.radius = 1.0;
  ReferenceObjects r;
  std::string err;
  ASSERT_TRUE(referenceObjectsFromLabels(c, labels, s, r, err)) << err;
  std::set<int> building, vegetation;
  for (std::size_t i = 0; i < labels.size(); ++i)
    (labels[i] == 6 ? building : vegetation).insert(r.object_of[i]);
  EXPECT_EQ(building.size(), 1u);
  EXPECT_EQ(vegetation.size(), 2u);
  // Without plan connectivity the building is cut at its roof step.
  s.plan_connected_groups.clear();
  ASSERT_TRUE(referenceObjectsFromLabels(c, labels, s, r, err)) << err;
  building.clear();
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] == 6)
      building.insert(r.object_of[i]);
  EXPECT_EQ(building.size(), 2u);
}

TEST(ReferenceObjects, FromIdsTakeTheMajorityGroup)
{
  // id 7: 3 vegetation points + 1 ground point -> vegetation; id −1 and code 1 unlabelled.
  const std::vector<int> ids{7, 7, 7, 7, 3, 3, -1, 3};
  const std::vector<int> labels{5, 4, 3, 2, 6, 6, 2, 1};
  ReferenceObjects r;
  std::string err;
  ASSERT_TRUE(referenceObjectsFromIds(ids, labels, defaultClassGroups(), defaultExcludedCodes(), r, err));
  ASSERT_EQ(r.objects(), 2u);
  EXPECT_EQ(r.group_of_object[0], 2);  // vegetation
  EXPECT_EQ(r.size[0], 4u);
  EXPECT_EQ(r.group_of_object[1], 1);  // building
  EXPECT_EQ(r.size[1], 2u);
  EXPECT_EQ(r.object_of[6], ReferenceObjects::kUnlabelled);
  EXPECT_EQ(r.object_of[7], ReferenceObjects::kUnlabelled);
}

TEST(VoxelBaseline, SegmentCountMatchesAndCellsPartitionTheCloud)
{
  pcl::PointCloud<pcl::PointXYZ> c;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      c.push_back(pcl::PointXYZ(0.25f * i, 0.25f * j, 0.1f * static_cast<float>((i * j) % 7)));
  c.push_back(pcl::PointXYZ(std::nanf(""), 0.f, 0.f));
  double size = 0.0;
  const auto segs = voxelSegmentsWithCount(c, 100, size);
  EXPECT_NEAR(static_cast<double>(segs.size()), 100.0, 10.0);
  std::vector<int> count(c.size(), 0);
  for (const auto& s : segs) {
    Eigen::Vector3f lo = c[s.indices[0]].getVector3fMap(), hi = lo;
    for (int i : s.indices) {
      ++count[static_cast<std::size_t>(i)];
      lo = lo.cwiseMin(c[i].getVector3fMap());
      hi = hi.cwiseMax(c[i].getVector3fMap());
    }
    EXPECT_LE((hi - lo).maxCoeff(), size + 1e-6);
  }
  for (std::size_t i = 0; i + 1 < c.size(); ++i)
    EXPECT_EQ(count[i], 1) << i;
  EXPECT_EQ(count.back(), 0);  // the NaN point is in no segment
}
