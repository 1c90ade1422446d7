// Raster geometry (maps/raster.h): grids snap to whole cells, positions map to the cell that
// covers them, accumulation gives per-cell means or the value of largest magnitude.
#include <pcl_ls3d/maps/raster.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ls3d::maps;

TEST(GridGeometry, CoversTheBoxWithCellsSnappedToMultiplesOfTheCell)
{
  const GridGeometry g = GridGeometry::covering({770501.3, 6277550.2}, {770549.9, 6277599.7}, 2.0);
  ASSERT_TRUE(g.valid());
  EXPECT_DOUBLE_EQ(g.min_x, 770500.0);
  EXPECT_DOUBLE_EQ(g.max_y, 6277600.0);
  EXPECT_EQ(g.cols, 25);
  EXPECT_EQ(g.rows, 25);
  int c = -1, r = -1;
  ASSERT_TRUE(g.cellOf(770501.3, 6277550.2, c, r));  // the box's corners are inside
  EXPECT_EQ(c, 0);
  EXPECT_EQ(r, 24);
  ASSERT_TRUE(g.cellOf(770549.9, 6277599.7, c, r));
  EXPECT_EQ(c, 24);
  EXPECT_EQ(r, 0);
  EXPECT_FALSE(g.cellOf(770499.9, 6277560.0, c, r));
  const Eigen::Vector2d centre = g.centre(0, 0);
  EXPECT_DOUBLE_EQ(centre.x(), 770501.0);
  EXPECT_DOUBLE_EQ(centre.y(), 6277599.0);
  const auto gt = g.geoTransform();
  EXPECT_DOUBLE_EQ(gt[0], 770500.0);
  EXPECT_DOUBLE_EQ(gt[5], -2.0);
}

TEST(GridGeometry, InvalidInputGivesAnInvalidGrid)
{
  EXPECT_FALSE(GridGeometry::covering({0, 0}, {1, 1}, 0.0).valid());
  EXPECT_FALSE(GridGeometry::covering({0, 0}, {-1, 1}, 1.0).valid());
  EXPECT_FALSE(GridGeometry::covering({0, NAN}, {1, 1}, 1.0).valid());
}

TEST(RasterAccumulator, MeanAndLargestMagnitudePerCell)
{
  const GridGeometry g = GridGeometry::covering({0, 0}, {3.9, 1.9}, 1.0);
  RasterAccumulator mean(g), worst(g, RasterAccumulator::Mode::MAX_ABS);
  for (auto* acc : {&mean, &worst}) {
    acc->add(0.5, 1.5, 0.1);
    acc->add(0.6, 1.4, -0.3);
    acc->add(2.5, 0.5, 0.2);
    acc->add(99.0, 0.5, 5.0);  // outside: ignored
    acc->add(1.5, 0.5, NAN);   // not finite: ignored
  }
  const Raster m = mean.result(), w = worst.result();
  EXPECT_FLOAT_EQ(m.at(0, 0), -0.1f);
  EXPECT_FLOAT_EQ(w.at(0, 0), -0.3f);
  EXPECT_FLOAT_EQ(m.at(2, 1), 0.2f);
  EXPECT_TRUE(std::isnan(m.at(1, 1)));
  EXPECT_EQ(m.validCells(), 2u);
  EXPECT_EQ(mean.result(2).validCells(), 1u);  // only the cell with two samples
  const auto range = m.range();
  EXPECT_FLOAT_EQ(range.first, -0.1f);
  EXPECT_FLOAT_EQ(range.second, 0.2f);
  // Merging rasters on one grid keeps the conservative value.
  RasterAccumulator mosaic(g, RasterAccumulator::Mode::MAX_ABS);
  mosaic.addRaster(m);
  mosaic.addRaster(w);
  EXPECT_FLOAT_EQ(mosaic.result().at(0, 0), -0.3f);
}
