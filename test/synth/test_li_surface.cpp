// Tests of makeLiSurface (Li et al. 2001 test surface).
#include <pcl_ls3d/synth/li_surface.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pcl_ls3d;
using namespace pcl_ls3d::synth;

// 2500 nodes, 100-unit spacing, relief exactly 5000, mask share as requested.
TEST(Synth, LiSurfaceShape)
{
  LiSurfaceSettings s;
  s.deformation_percent = 16.0;
  const LiSurface li = makeLiSurface(s);
  ASSERT_EQ(li.reference->size(), 2500u);
  ASSERT_EQ(li.mate->size(), 2500u);
  float zmin = 1e30f, zmax = -1e30f;
  for (const auto& p : *li.reference) {
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
  }
  EXPECT_NEAR(zmax - zmin, 5000.0, 0.01);  // float rounding only
  EXPECT_NEAR((*li.reference)[1].x - (*li.reference)[0].x, 100.0, 1e-3);
  EXPECT_EQ(li.deformed_indices.size(), 400u);  // 16 % of 2500, exact by construction
  EXPECT_NEAR(li.percent, 16.0, 1e-9);
}

// Inside the mask, truth.apply(mate) − reference has mean c·σ; outside it is N(0, σ) noise.
TEST(Synth, LiSurfaceTruthAndDeformation)
{
  LiSurfaceSettings s;
  s.deformation_percent = 25.0;
  s.position = DeformationPosition::LOWER_LEFT;
  const LiSurface li = makeLiSurface(s);
  double in_sum = 0.0, out_sq = 0.0, max_xy = 0.0;
  std::size_t n_in = 0, n_out = 0;
  for (std::size_t i = 0; i < li.mate->size(); ++i) {
    const Eigen::Vector3d m = li.truth.apply((*li.mate)[i].getVector3fMap().cast<double>());
    const Eigen::Vector3d r = (*li.reference)[i].getVector3fMap().cast<double>();
    max_xy = std::max(max_xy, (m - r).head<2>().norm());
    const double dz = m.z() - r.z();
    if (li.deformed[i]) {
      in_sum += dz;
      ++n_in;
    } else {
      out_sq += dz * dz;
      ++n_out;
    }
  }
  // Float coordinates (|x| ≤ 2500) round to ≤ 1.2e-4 per axis.
  EXPECT_LT(max_xy, 1e-3);
  // Mean of 625 draws of N(cσ, σ) + N(0, σ): sd = σ√2/25 ≈ 1.1 units; tolerance 5 units.
  EXPECT_NEAR(in_sum / n_in, s.deformation_c * s.noise_sigma, 5.0);
  // RMS of 1875 N(0, σ) draws: within ~2 % of σ; tolerance 8 %.
  EXPECT_NEAR(std::sqrt(out_sq / n_out), s.noise_sigma, 0.08 * s.noise_sigma);
  // The mate is really moved: without truth the nodes are off by tens of units.
  const double raw = ((*li.mate)[0].getVector3fMap() - (*li.reference)[0].getVector3fMap()).norm();
  EXPECT_GT(raw, 10.0);
}

// The gathered patch sits at the requested anchor (lower-left: small x and y; centre: central).
TEST(Synth, LiSurfacePositions)
{
  LiSurfaceSettings s;
  s.deformation_percent = 9.0;
  for (int p = 0; p < 9; ++p) {
    s.position = static_cast<DeformationPosition>(p);
    const LiSurface li = makeLiSurface(s);
    ASSERT_EQ(li.deformed_indices.size(), 225u);
    double cx = 0.0, cy = 0.0;
    for (int i : li.deformed_indices) {
      cx += (*li.reference)[i].x;
      cy += (*li.reference)[i].y;
    }
    cx /= 225.0;
    cy /= 225.0;
    const double ex = (p % 3 - 1), ey = (1 - p / 3);  // expected sign of the centroid
    EXPECT_TRUE(ex == 0 ? std::abs(cx) < 100.0 : cx * ex > 1500.0) << toString(s.position);
    EXPECT_TRUE(ey == 0 ? std::abs(cy) < 100.0 : cy * ey > 1500.0) << toString(s.position);
    DeformationPosition back;
    ASSERT_TRUE(parseDeformationPosition(toString(s.position), back));
    EXPECT_EQ(back, s.position);
  }
}

TEST(Synth, LiSurfaceDeterministic)
{
  LiSurfaceSettings s;
  const LiSurface a = makeLiSurface(s), b = makeLiSurface(s);
  s.seed = 2;
  const LiSurface c = makeLiSurface(s);
  for (std::size_t i = 0; i < a.mate->size(); ++i)
    ASSERT_EQ((*a.mate)[i].z, (*b.mate)[i].z);
  EXPECT_NE((*a.mate)[100].z, (*c.mate)[100].z);
  s.deformation_percent = 120.0;
  EXPECT_TRUE(makeLiSurface(s).mate->empty());
}
