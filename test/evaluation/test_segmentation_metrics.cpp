// Per-class P/R/F1 on hand-computed confusion cases, the class-group parser, and the
// segment <-> label conversions. All counts are integers: scores are compared to 1e-12.
#include <pcl_ls3d/evaluation/segmentation_labels.h>
#include <pcl_ls3d/evaluation/segmentation_metrics.h>
#include <pcl_ls3d/evaluation/segmentation_report.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d::evaluation;

namespace {
pcl::PointIndices
seg(std::vector<int> idx)
{
  pcl::PointIndices p;
  p.indices = std::move(idx);
  return p;
}
}  // namespace

TEST(SegmentationMetrics, HandComputedConfusion)
{
  //  point:   0  1  2  3  4  5  6  7  8  9
  //  label:   2  2  2  2  6  6  6  5  5  1
  // S0 = {0,1,2,4}: 3 ground + 1 building -> ground. S1 = {5,6,7}: 2 building + 1 veg -> building.
  // S2 = {9}: only an unclassified point -> not evaluated. Points 3 and 8 are in no segment.
  const std::vector<int> labels{2, 2, 2, 2, 6, 6, 6, 5, 5, 1};
  SegmentationEvaluation e;
  std::string err;
  ASSERT_TRUE(evaluateSegmentation({seg({0, 1, 2, 4}), seg({5, 6, 7}), seg({9})}, labels, {}, e, err));
  ASSERT_EQ(e.classes.size(), 4u);
  const ClassScores& g = e.classes[0];
  const ClassScores& b = e.classes[1];
  const ClassScores& v = e.classes[2];
  const ClassScores& w = e.classes[3];
  // ground: TP 3 (0,1,2), FP 1 (4), FN 1 (3 unsegmented) -> P = R = F1 = 0.75.
  EXPECT_EQ(g.tp, 3u);
  EXPECT_EQ(g.fp, 1u);
  EXPECT_EQ(g.fn, 1u);
  EXPECT_NEAR(g.precision, 0.75, 1e-12);
  EXPECT_NEAR(g.recall, 0.75, 1e-12);
  EXPECT_NEAR(g.f1, 0.75, 1e-12);
  // building: TP 2 (5,6), FP 1 (7), FN 1 (4 went to ground) -> 2/3 each.
  EXPECT_NEAR(b.precision, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(b.recall, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(b.f1, 2.0 / 3.0, 1e-12);
  // vegetation: nothing predicted, 2 reference points -> P undefined, R = F1 = 0.
  EXPECT_TRUE(std::isnan(v.precision));
  EXPECT_DOUBLE_EQ(v.recall, 0.0);
  EXPECT_DOUBLE_EQ(v.f1, 0.0);
  // wire: absent everywhere -> all undefined.
  EXPECT_TRUE(std::isnan(w.precision) && std::isnan(w.recall) && std::isnan(w.f1));

  EXPECT_EQ(e.segments, 3u);
  EXPECT_EQ(e.segments_evaluated, 2u);
  EXPECT_EQ(e.points_evaluated, 9u);
  EXPECT_EQ(e.points_unsegmented, 2u);
  EXPECT_EQ(g.segments, 1u);
  // Confusion row "ground": 3 -> ground, 1 -> none (column G + 1 = 5).
  EXPECT_EQ(e.confusion[0][0], 3u);
  EXPECT_EQ(e.confusion[0][5], 1u);
  EXPECT_EQ(e.confusion[1][0], 1u);  // building point 4 predicted ground
}

TEST(SegmentationMetrics, OtherCodesTiesAndDuplicates)
{
  // Code 31 (in no group) votes and is an FP of the ground segment it sits in; a segment with a
  // 31 majority maps to "other". A 1:1 ground/building tie goes to ground (listed first).
  //  point:  0  1   2   3   4  5
  //  label:  2  2  31  31  31  6
  const std::vector<int> labels{2, 2, 31, 31, 31, 6};
  SegmentationEvaluation e;
  std::string err;
  ASSERT_TRUE(evaluateSegmentation({seg({0, 2}), seg({3, 4, 1}), seg({5, 0})}, labels, {}, e, err));
  // S0 {0,2}: ground 1 vs other 1 -> ground (named groups win ties). S1 {3,4,1}: other.
  // S2 {5,0}: point 0 already claimed (duplicate); votes building 1, ground 1 -> ground.
  EXPECT_EQ(e.points_duplicated, 1u);
  const ClassScores& g = e.classes[0];
  EXPECT_EQ(g.tp, 1u);  // point 0
  EXPECT_EQ(g.fp, 2u);  // point 2 (other) and point 5 (building)
  EXPECT_EQ(g.fn, 1u);  // point 1 went to "other"
  EXPECT_EQ(e.other.tp, 2u);
  EXPECT_EQ(e.other.segments, 1u);
  EXPECT_EQ(e.classes[1].fn, 1u);
  EXPECT_DOUBLE_EQ(e.classes[1].recall, 0.0);
}

TEST(SegmentationMetrics, PerfectAndCustomGroups)
{
  // Cars (64) as a configured group; a perfect segmentation scores 1 everywhere it is defined.
  const std::vector<int> labels{2, 2, 64, 64, 6};
  SegmentationEvaluationSettings s;
  std::string err;
  ASSERT_TRUE(parseClassGroups("ground=2,building=6,car=64", s.groups, err)) << err;
  SegmentationEvaluation e;
  ASSERT_TRUE(evaluateSegmentation({seg({0, 1}), seg({2, 3}), seg({4})}, labels, s, e, err));
  for (const auto& c : e.classes) {
    EXPECT_DOUBLE_EQ(c.f1, 1.0) << c.name;
    EXPECT_DOUBLE_EQ(c.precision, 1.0) << c.name;
  }
  EXPECT_EQ(e.classes[2].name, "car");
  // The table prints every class and method row.
  e.method = "perfect";
  const std::string t = formatSegmentationTable({e});
  EXPECT_NE(t.find("car P/R/F1"), std::string::npos);
  EXPECT_NE(t.find("100.0 / 100.0 / 100.0"), std::string::npos);
  EXPECT_FALSE(describeConfusion(e).empty());
}

TEST(SegmentationMetrics, MinSegmentSizeTurnsFragmentsIntoFalseNegatives)
{
  // Ground 0..3 in one segment of 4, building 4 and 5 as two single-point segments.
  // With min_segment_size 2 the singletons are ignored: building TP 0, FN 2.
  const std::vector<int> labels{2, 2, 2, 2, 6, 6};
  SegmentationEvaluationSettings s;
  s.min_segment_size = 2;
  SegmentationEvaluation e;
  std::string err;
  ASSERT_TRUE(evaluateSegmentation({seg({0, 1, 2, 3}), seg({4}), seg({5})}, labels, s, e, err));
  EXPECT_EQ(e.segments_too_small, 2u);
  EXPECT_EQ(e.points_unsegmented, 2u);
  EXPECT_EQ(e.classes[1].fn, 2u);
  EXPECT_DOUBLE_EQ(e.classes[1].f1, 0.0);
  EXPECT_DOUBLE_EQ(e.classes[0].f1, 1.0);
  // Without the minimum the same fragments score perfectly (why the option exists).
  ASSERT_TRUE(evaluateSegmentation({seg({0, 1, 2, 3}), seg({4}), seg({5})}, labels, {}, e, err));
  EXPECT_DOUBLE_EQ(e.classes[1].f1, 1.0);
}

TEST(SegmentationMetrics, BadInput)
{
  SegmentationEvaluation e;
  std::string err;
  EXPECT_FALSE(evaluateSegmentation({seg({0, 7})}, {2, 2}, {}, e, err));
  EXPECT_NE(err.find("outside"), std::string::npos);
  EXPECT_FALSE(evaluateSegmentation({seg({-1})}, {2}, {}, e, err));
  // No segments at all: every evaluated point is a false negative.
  ASSERT_TRUE(evaluateSegmentation({}, {2, 2, 6}, {}, e, err));
  EXPECT_EQ(e.points_unsegmented, 3u);
  EXPECT_DOUBLE_EQ(e.classes[0].recall, 0.0);
  // Empty everything is defined too.
  ASSERT_TRUE(evaluateSegmentation({}, {}, {}, e, err));
  EXPECT_EQ(e.points_evaluated, 0u);
}

// Predicted classes point by point: a predicted code counts for its group (5 and 3 both for
// vegetation), an unclassified prediction (1, excluded) is no prediction, a code in no group
// (64) predicts "other"; reference points with excluded codes are left out.
TEST(SegmentationMetrics, ClassificationPointByPoint)
{
  //  point:       0  1  2  3  4  5  6  7  8
  //  reference:   2  2  2  6  6  6  3  5  1
  //  predicted:   2  2  6  6  6  1  5 64  6
  const std::vector<int> reference{2, 2, 2, 6, 6, 6, 3, 5, 1};
  const std::vector<int> predicted{2, 2, 6, 6, 6, 1, 5, 64, 6};
  SegmentationEvaluation e;
  std::string err;
  ASSERT_TRUE(evaluateClassification(predicted, reference, {}, e, err)) << err;
  ASSERT_EQ(e.classes.size(), 4u);
  EXPECT_EQ(e.points_evaluated, 8u);
  EXPECT_EQ(e.points_unsegmented, 1u);  // point 5
  // ground: TP 2, FP 0, FN 1 (point 2 predicted building).
  EXPECT_EQ(e.classes[0].tp, 2u);
  EXPECT_EQ(e.classes[0].fp, 0u);
  EXPECT_EQ(e.classes[0].fn, 1u);
  // building: TP 2 (3, 4), FP 1 (point 2; point 8 is excluded), FN 1 (point 5, none).
  EXPECT_EQ(e.classes[1].tp, 2u);
  EXPECT_EQ(e.classes[1].fp, 1u);
  EXPECT_EQ(e.classes[1].fn, 1u);
  EXPECT_NEAR(e.classes[1].f1, 4.0 / 6.0, 1e-12);
  // vegetation: TP 1 (point 6), FN 1 (point 7 predicted "other").
  EXPECT_EQ(e.classes[2].tp, 1u);
  EXPECT_EQ(e.classes[2].fn, 1u);
  EXPECT_EQ(e.other.predicted_points, 1u);
  EXPECT_FALSE(evaluateClassification({2, 2}, reference, {}, e, err));
  EXPECT_NE(err.find("2 predicted classes for 9 reference labels"), std::string::npos) << err;

  // A group naming code 1 scores the reference's code 1 (IGN's parked cars); a prediction of
  // 1 (unclassified) or 0 (no segment) is still no prediction, not a car.
  SegmentationEvaluationSettings cars;
  ASSERT_TRUE(parseClassGroups("ground=2,car=1", cars.groups, err)) << err;
  ASSERT_TRUE(evaluateClassification({1, 1, 0, 1, 1}, {1, 1, 1, 2, 2}, cars, e, err)) << err;
  EXPECT_EQ(e.classes[1].tp, 0u);
  EXPECT_EQ(e.classes[1].fp, 0u);
  EXPECT_EQ(e.classes[1].fn, 3u);
  EXPECT_EQ(e.classes[0].fn, 2u);
  EXPECT_EQ(e.points_unsegmented, 5u);
}

TEST(SegmentationClasses, Parser)
{
  std::vector<ClassGroup> g;
  std::string err;
  ASSERT_TRUE(parseClassGroups("ground=2,vegetation=3-5,wire=14+15", g, err)) << err;
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[1].codes, (std::vector<int>{3, 4, 5}));
  EXPECT_EQ(g[2].codes, (std::vector<int>{14, 15}));
  EXPECT_FALSE(parseClassGroups("ground", g, err));
  EXPECT_FALSE(parseClassGroups("a=2,a=3", g, err));
  EXPECT_FALSE(parseClassGroups("a=2,b=1-3", g, err));  // 2 in two groups
  EXPECT_FALSE(parseClassGroups("a=5-3", g, err));
  EXPECT_FALSE(parseClassGroups("a=300", g, err));
  EXPECT_FALSE(parseClassGroups("", g, err));
  const ClassLookup lookup(defaultClassGroups(), defaultExcludedCodes());
  EXPECT_EQ(lookup.groupOf(4), 2);
  EXPECT_EQ(lookup.groupOf(1), ClassLookup::kExcluded);
  EXPECT_EQ(lookup.groupOf(31), ClassLookup::kOther);
  EXPECT_EQ(lookup.groupOf(-3), ClassLookup::kExcluded);
}

TEST(SegmentationLabels, RoundTripAndColours)
{
  const std::vector<pcl::PointIndices> segs{seg({4, 0}), seg({2}), seg({})};
  const auto labels = labelsFromSegments(segs, 6);
  EXPECT_EQ(labels, (std::vector<std::uint32_t>{1, 0, 2, 0, 1, 0}));
  const auto back = segmentsFromLabels(labels);
  ASSERT_EQ(back.size(), 2u);  // the empty segment has no label to come back from
  EXPECT_EQ(back[0].indices, (std::vector<int>{0, 4}));
  EXPECT_EQ(back[1].indices, (std::vector<int>{2}));
  EXPECT_EQ(segmentColour(0), 0x808080u);
  EXPECT_NE(segmentColour(1), segmentColour(2));
  EXPECT_LE(segmentColour(12345), 0xFFFFFFu);
}
