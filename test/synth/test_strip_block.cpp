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
    const double overlap = (extent[k].second - extent[k + 1].first) / (extent[k].second - extent[k].first);
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
    EXPECT_NEAR(terrainRms(block, k, block.strips[k].transform), s.noise_sigma, 0.1 * s.noise_sigma);
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

// Each scan line gets its own sub-spacing offset (u across, v along, read back from the true
// position of the line's first point; even lines, which sweep left to right in ZIGZAG); without
// line_phase every line has u = v = ½. The truths do not depend on the phases.
TEST(Synth, StripLinePhases)
{
  auto s = smallStrips();
  s.noise_sigma = 0.0;
  const int lines = 20;
  auto phases = [&s, lines](const StripBlock& b, std::size_t strip) {
    const StripTruth& st = b.strips[strip];
    const Eigen::Vector2d a(-b.direction.y(), b.direction.x());
    const double n_c = static_cast<double>(st.points_per_line);
    const double swath = (st.footprint[0] - st.footprint[1]).norm();
    const double length = (st.footprint[3] - st.footprint[0]).norm();
    const double da = 1.0 / (s.density * swath / n_c);
    std::vector<Eigen::Vector2d> uv;
    for (int k = 0; k < lines; k += 2) {
      const std::size_t i = st.first_index + static_cast<std::size_t>(k) * st.points_per_line;
      const Eigen::Vector3d p = st.transform.apply((*b.cloud)[i].getVector3fMap().cast<double>());
      const Eigen::Vector2d rel = p.head<2>() - st.centre.head<2>();
      const double u = (a.dot(rel) / swath + 0.5) * n_c;
      const double v = (b.direction.dot(rel) + 0.5 * length) / da - k - 0.5 / n_c + 0.5;
      uv.emplace_back(u, v);
    }
    return uv;
  };
  s.line_phase = false;
  const StripBlock regular = makeStripBlock(s);
  s.line_phase = true;
  const StripBlock moved = makeStripBlock(s);
  std::vector<Eigen::Vector2d> first_lines;
  for (std::size_t k = 0; k < moved.strips.size(); ++k) {
    for (const auto& uv : phases(regular, k))
      EXPECT_LT((uv - Eigen::Vector2d::Constant(0.5)).norm(), 1e-3);
    const auto uv = phases(moved, k);
    double spread = 0.0;
    for (const auto& p : uv) {
      EXPECT_TRUE(p.minCoeff() > -1e-3 && p.maxCoeff() < 1.0 + 1e-3) << p.transpose();
      spread = std::max(spread, (p - uv[0]).norm());
    }
    EXPECT_GT(spread, 0.1) << "strip " << k << ": its lines share one lattice";
    for (const auto& p : first_lines)
      EXPECT_GT((uv[0] - p).norm(), 0.01) << "strip " << k << " starts on another strip's lattice";
    first_lines.push_back(uv[0]);
    EXPECT_LT((moved.strips[k].transform.matrix() - regular.strips[k].transform.matrix()).norm(), 1e-15);
  }
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

// Cross strips: flown across the row, spanning every parallel strip, with their own ids, counts
// and truths, after the parallel strips in the cloud; the parallel strips are unchanged.
TEST(Synth, CrossStrips)
{
  auto s = smallStrips();
  const StripBlock plain = makeStripBlock(s);
  s.cross_strips = 2;
  const StripBlock block = makeStripBlock(s);
  ASSERT_EQ(block.strips.size(), 5u);
  for (std::size_t i = 0; i < plain.cloud->size(); i += 11)
    ASSERT_EQ((*plain.cloud)[i].z, (*block.cloud)[i].z);  // parallel strips as without cross strips
  const double across = 2 * s.swath_width * (1.0 - s.side_overlap) + s.swath_width;
  const Eigen::Vector2d a(-block.direction.y(), block.direction.x());
  for (std::size_t k = 3; k < 5; ++k) {
    const StripTruth& st = block.strips[k];
    EXPECT_TRUE(st.cross);
    EXPECT_EQ(st.point_source_id, 1 + k);
    EXPECT_EQ(st.first_index, block.strips[k - 1].first_index + block.strips[k - 1].point_count);
    EXPECT_NEAR(static_cast<double>(st.point_count), s.density * across * s.swath_width,
                0.005 * s.density * across * s.swath_width);
    // Its first and last scan lines lie at the two outer edges of the row (true frame).
    const auto first = (*block.cloud)[st.first_index],
               last = (*block.cloud)[st.first_index + st.point_count - 1];
    const Eigen::Vector3d p0 = st.transform.apply(first.getVector3fMap().cast<double>());
    const Eigen::Vector3d p1 = st.transform.apply(last.getVector3fMap().cast<double>());
    EXPECT_NEAR(a.dot(p1.head<2>() - p0.head<2>()), across, 2.0);
    EXPECT_NEAR(block.direction.dot(st.centre.head<2>()), (k == 3 ? -0.25 : 0.25) * s.strip_length, 1e-9);
  }
  EXPECT_EQ(block.cloud->size(), block.strips[4].first_index + block.strips[4].point_count);
}

// Explicit errors act about each strip's centre: t_centre is the error's translation.
TEST(Synth, StripErrorsAboutTheCentre)
{
  auto s = smallStrips();
  s.fix_first = false;
  Vector7d e;
  e << 1.0, -2.0, 3.0, 1e-4, -2e-4, 3e-4, 1.00005;
  s.errors = {e, e, e};
  const StripBlock block = makeStripBlock(s);
  for (const StripTruth& st : block.strips) {
    EXPECT_LT((st.t_centre - e.head<3>()).norm(), 1e-9);
    EXPECT_NEAR(st.transform.m, e[SCALE], 1e-15);
  }
  s.errors.resize(2);
  EXPECT_FALSE(s.isValid());
}

// Zuo-like scenes: the urban one has roofs, tree crowns (class 5) and roads free of buildings; the
// mountainous one has terraces (flat treads) and scarps, and far more relief.
TEST(Synth, UrbanAndMountainScenes)
{
  auto s = smallStrips();
  s.noise_sigma = 0.0;
  setScene(s, LandscapeType::URBAN);
  const StripBlock urban = makeStripBlock(s);
  std::map<int, std::size_t> classes;
  for (const auto& p : *urban.cloud)
    ++classes[p.classification];
  EXPECT_GT(classes[6], urban.cloud->size() / 20);
  EXPECT_GT(classes[5], urban.cloud->size() / 100);
  EXPECT_GT(classes[2], urban.cloud->size() / 4);
  ASSERT_TRUE(urban.landscape);
  EXPECT_GT(urban.landscape->treeCount(), 10u);
  for (const auto& b : urban.surface->buildings().buildings())
    EXPECT_FALSE(urban.landscape->onRoad(b.centre.x(), b.centre.y(), b.radius()));

  setScene(s, LandscapeType::MOUNTAIN);
  const StripBlock mountain = makeStripBlock(s);
  const Landscape& m = *mountain.landscape;
  // Terraces: the ground is flat (within 1 mm over 1 m) on most of the area, and it spans tens of m.
  int flat = 0, n = 0;
  double lo = 1e300, hi = -1e300;
  for (double x = -90.0; x <= 90.0; x += 3.0)
    for (double y = -90.0; y <= 90.0; y += 3.0, ++n) {
      const double h = m.groundHeight(x, y);
      lo = std::min(lo, h);
      hi = std::max(hi, h);
      flat +=
          std::abs(m.groundHeight(x + 1.0, y) - h) < 1e-3 && std::abs(m.groundHeight(x, y + 1.0) - h) < 1e-3;
    }
  EXPECT_GT(flat, n / 3);
  EXPECT_GT(hi - lo, 20.0);
  EXPECT_EQ(m.ground().scarps().size(), 4u);
}

// Landforms on a flat terrain: a scarp raises its positive side by its height over its width,
// continuously; terraces turn a slope into flat treads and steep risers of the step height.
TEST(Synth, ScarpsAndTerraces)
{
  LandformSettings f;
  f.scarps = 1;
  const Eigen::AlignedBox2d region(Eigen::Vector2d(-100, -100), Eigen::Vector2d(100, 100));
  const Ground flat(Terrain(1, 0.0), f, region, 7);
  const Scarp& sc = flat.scarps().at(0);
  const Eigen::Vector2d lo = sc.point - 2.0 * sc.normal, mid = sc.point, hi = sc.point + 2.0 * sc.normal;
  EXPECT_NEAR(flat.height(lo.x(), lo.y()), 0.0, 1e-12);
  EXPECT_NEAR(flat.height(mid.x(), mid.y()), 0.5 * sc.height, 1e-9);
  EXPECT_NEAR(flat.height(hi.x(), hi.y()), sc.height, 1e-12);
  EXPECT_GE(sc.height, f.min_scarp_height);
  EXPECT_LE(sc.height, f.max_scarp_height);

  LandformSettings t;
  t.terrace_step = 2.0;
  t.terrace_riser = 0.25;
  const Ground terraced(Terrain(3, 40.0, 200.0), t, region, 7);
  int on_step = 0, n = 0;
  for (double x = -80.0; x <= 80.0; x += 0.7)
    for (double y = -80.0; y <= 80.0; y += 5.3, ++n) {
      const double h = terraced.height(x, y);
      on_step += std::abs(h / 2.0 - std::round(h / 2.0)) < 1e-9;
    }
  EXPECT_GT(on_step, n / 2);  // treads: (1 − riser share) of the slope, at multiples of the step
}
