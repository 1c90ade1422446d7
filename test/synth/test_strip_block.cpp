// Tests of makeStripBlock: strip ids, counts, side overlap, per-strip truth, time, pattern.
#include <pcl_ls3d/synth/strip_block.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace pcl_ls3d;
using namespace pcl_ls3d::synth;

namespace {

StripSettings
smallStrips()
{
  StripSettings s;
  s.seed = 5;
  s.num_strips = 3;
  s.heading = 0.4;  // not axis-aligned, so direction handling is exercised
  s.strip_length = 200.0;
  s.swath_width = 100.0;
  s.side_overlap = 0.3;
  s.density = 2.0;
  s.shift_sigma = 0.5;  // large enough to be seen against σ = 0.05
  s.building_settings.per_hectare = 4.0;
  return s;
}

/// RMS of the vertical residual to the terrain (normal-projected) of terrain points, after T.
double
terrainRms(const StripBlock& block, std::size_t s, const SimilarityTransform& T)
{
  const StripTruth& st = block.strips[s];
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = st.first_index; i < st.first_index + st.point_count; ++i) {
    const Eigen::Vector3d p = T.apply((*block.cloud)[i].getVector3fMap().cast<double>());
    if (block.surface->buildings().find(p.x(), p.y(), 2.0) >= 0)
      continue;  // roofs and their edges
    const auto& terrain = block.surface->terrain();
    const double r = (p.z() - terrain.height(p.x(), p.y())) * terrain.normal(p.x(), p.y()).z();
    sum += r * r;
    ++n;
  }
  return std::sqrt(sum / std::max<std::size_t>(n, 1));
}

}  // namespace

// One point_source_id per strip, counts as the nominal density, time increasing in each strip.
TEST(Synth, StripIdsCountsAndTime)
{
  const auto s = smallStrips();
  const StripBlock block = makeStripBlock(s);
  ASSERT_EQ(block.strips.size(), 3u);
  std::map<std::uint16_t, std::size_t> counts;
  for (const auto& p : *block.cloud)
    ++counts[p.point_source_id];
  ASSERT_EQ(counts.size(), 3u);
  for (const auto& st : block.strips) {
    EXPECT_EQ(counts[st.point_source_id], st.point_count);
    // Scan-line rounding changes the count by less than one line (≤ 0.5 % here).
    EXPECT_NEAR(static_cast<double>(st.point_count), s.density * s.strip_length * s.swath_width,
                0.005 * s.density * s.strip_length * s.swath_width);
    for (std::size_t i = st.first_index + 1; i < st.first_index + st.point_count; ++i)
      ASSERT_GT((*block.cloud)[i].gps_time, (*block.cloud)[i - 1].gps_time);
  }
  EXPECT_GT(block.strips[1].start_time, block.strips[0].end_time);
  // Density from the data: strip 1 (identity truth) points within 30 m × 30 m of its centre.
  const StripTruth& st = block.strips[0];
  std::size_t inside = 0;
  for (std::size_t i = st.first_index; i < st.first_index + st.point_count; ++i) {
    const Eigen::Vector2d v = (*block.cloud)[i].getVector2fMap().cast<double>() - st.centre.head<2>();
    const Eigen::Vector2d a(-block.direction.y(), block.direction.x());
    inside += std::abs(v.dot(block.direction)) < 15.0 && std::abs(v.dot(a)) < 15.0;
  }
  // A regular pattern: the count in the window is within one scan line (~30 points) of 1800.
  EXPECT_NEAR(inside / 900.0, s.density, 0.05 * s.density);
}

// Side overlap measured from the data (across-track extents of the true points) ≈ requested.
TEST(Synth, StripSideOverlap)
{
  const auto s = smallStrips();
  const StripBlock block = makeStripBlock(s);
  const Eigen::Vector2d a(-block.direction.y(), block.direction.x());
  std::vector<std::pair<double, double>> extent;
  for (std::size_t k = 0; k < block.strips.size(); ++k) {
    const StripTruth& st = block.strips[k];
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = st.first_index; i < st.first_index + st.point_count; ++i) {
      const Eigen::Vector3d p = st.transform.apply((*block.cloud)[i].getVector3fMap().cast<double>());
      const double c = a.dot(p.head<2>());
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
    extent.emplace_back(lo, hi);
  }
  for (std::size_t k = 0; k + 1 < extent.size(); ++k) {
    const double overlap =
        (extent[k].second - extent[k + 1].first) / (extent[k].second - extent[k].first);
    // Edge points sit half a point spacing (0.35 m) inside the swath; noise 0.05 m: ±0.01.
    EXPECT_NEAR(overlap, s.side_overlap, 0.01);
  }
}

// Applying each strip's truth puts its terrain points on the true terrain (RMS ≈ σ); without it
// the moved strips are off. Strip 1 is the fixed reference.
TEST(Synth, StripTruthApplied)
{
  const auto s = smallStrips();
  const StripBlock block = makeStripBlock(s);
  EXPECT_TRUE(block.strips[0].fixed);
  EXPECT_LT((block.strips[0].transform.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-15);
  for (std::size_t k = 0; k < block.strips.size(); ++k) {
    // ~30000 normal draws: RMS within ~1 % of σ; tolerance 10 %.
    EXPECT_NEAR(terrainRms(block, k, block.strips[k].transform), s.noise_sigma,
                0.1 * s.noise_sigma);
    // The centre-referenced shift is consistent with the transform.
    const StripTruth& st = block.strips[k];
    const Eigen::Vector3d x = st.centre + Eigen::Vector3d(10.0, -20.0, 3.0);
    const Eigen::Vector3d y =
        st.centre + st.t_centre + st.transform.m * (st.transform.rotation() * (x - st.centre));
    EXPECT_LT((y - st.transform.apply(x)).norm(), 1e-9);
  }
  EXPECT_GT(terrainRms(block, 1, SimilarityTransform()), 2.0 * s.noise_sigma);
}

// Same seed → identical; different seed → different; ZIGZAG and PARALLEL differ on odd lines only.
TEST(Synth, StripDeterminismAndPattern)
{
  auto s = smallStrips();
  const StripBlock a = makeStripBlock(s), b = makeStripBlock(s);
  ASSERT_EQ(a.cloud->size(), b.cloud->size());
  for (std::size_t i = 0; i < a.cloud->size(); i += 7)
    ASSERT_EQ((*a.cloud)[i].z, (*b.cloud)[i].z);
  s.seed = 6;
  const StripBlock c = makeStripBlock(s);
  EXPECT_NE((*a.cloud)[100].z, (*c.cloud)[100].z);

  s.seed = 5;
  s.noise_sigma = 0.0;
  s.pattern = ScanPattern::ZIGZAG;
  const StripBlock zig = makeStripBlock(s);
  s.pattern = ScanPattern::PARALLEL;
  const StripBlock par = makeStripBlock(s);
  const std::size_t n_c = zig.strips[0].points_per_line;
  // Line 0: identical; line 1: reversed sweep direction.
  EXPECT_EQ((*zig.cloud)[0].x, (*par.cloud)[0].x);
  EXPECT_GT(((*zig.cloud)[n_c].getVector3fMap() - (*par.cloud)[n_c].getVector3fMap()).norm(), 50.f);
}

TEST(Synth, StripInvalid)
{
  auto s = smallStrips();
  s.side_overlap = 1.0;
  EXPECT_TRUE(makeStripBlock(s).cloud->empty());
  s = smallStrips();
  s.transforms.resize(2);  // wrong size
  EXPECT_FALSE(s.isValid());
}
