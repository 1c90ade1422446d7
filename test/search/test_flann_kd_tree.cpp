// FlannKdTree must answer exactly as pcl::search::KdTree (the tree PCL's registration builds):
// the same neighbours at the same distances, indices into the input cloud past non-finite points
// and index subsets, and the base class's behaviour where it cannot take the direct path.
#include <pcl_ls3d/search/flann_kd_tree.h>

#include <pcl/point_representation.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr
randomCloudWithHoles(std::size_t n, unsigned seed)
{
  Cloud::Ptr cloud(new Cloud);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 10.0f);
  for (std::size_t i = 0; i < n; ++i)
    cloud->push_back(pcl::PointXYZ(u(rng), u(rng), 0.2f * u(rng)));
  for (std::size_t i = 7; i < n; i += 97)  // sensor dropouts, as in organised scans
    (*cloud)[i].y = std::numeric_limits<float>::quiet_NaN();
  cloud->is_dense = false;
  return cloud;
}

// Every answer is compared in distance (ties may come in another order) and each returned
// index must point at a finite input point at exactly the reported distance.
void
expectSameAnswers(const Cloud& cloud, const pcl::search::Search<pcl::PointXYZ>& pcl_tree,
                  const pcl::search::Search<pcl::PointXYZ>& ours)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 11.0f);
  for (int q = 0; q < 300; ++q) {
    const pcl::PointXYZ query(u(rng), u(rng), 0.2f * u(rng));
    pcl::Indices a, b;
    std::vector<float> da, db;
    for (int k : {1, 6, 40}) {
      ASSERT_EQ(pcl_tree.nearestKSearch(query, k, a, da), ours.nearestKSearch(query, k, b, db));
      ASSERT_EQ(da, db) << "k = " << k;
      for (std::size_t i = 0; i < b.size(); ++i)
        EXPECT_FLOAT_EQ((cloud[b[i]].getVector3fMap() - query.getVector3fMap()).squaredNorm(), db[i]);
    }
    for (unsigned max_nn : {0u, 5u}) {
      ASSERT_EQ(pcl_tree.radiusSearch(query, 0.8, a, da, max_nn),
                ours.radiusSearch(query, 0.8, b, db, max_nn));
      ASSERT_EQ(da, db) << "max_nn = " << max_nn;
      for (std::size_t i = 0; i < b.size(); ++i)
        EXPECT_FLOAT_EQ((cloud[b[i]].getVector3fMap() - query.getVector3fMap()).squaredNorm(), db[i]);
    }
  }
}

}  // namespace

TEST(FlannKdTree, AnswersAsPclKdTreeOnACloudWithNonFinitePoints)
{
  const Cloud::Ptr cloud = randomCloudWithHoles(5000, 1);
  pcl::search::KdTree<pcl::PointXYZ> pcl_tree;
  pcl_tree.setInputCloud(cloud);
  pcl_ls3d::search::FlannKdTree<pcl::PointXYZ> ours;
  ours.setInputCloud(cloud);
  expectSameAnswers(*cloud, pcl_tree, ours);
}

TEST(FlannKdTree, AnswersAsPclKdTreeOnAnIndexSubset)
{
  const Cloud::Ptr cloud = randomCloudWithHoles(4000, 2);
  pcl::IndicesPtr every_third(new pcl::Indices);
  for (int i = 0; i < static_cast<int>(cloud->size()); i += 3)
    every_third->push_back(i);
  pcl::search::KdTree<pcl::PointXYZ> pcl_tree;
  pcl_tree.setInputCloud(cloud, every_third);
  pcl_ls3d::search::FlannKdTree<pcl::PointXYZ> ours;
  ours.setInputCloud(cloud, every_third);
  expectSameAnswers(*cloud, pcl_tree, ours);

  pcl::Indices found;
  std::vector<float> d;
  ours.nearestKSearch(pcl::PointXYZ(5, 5, 1), 50, found, d);
  for (pcl::index_t i : found)
    EXPECT_EQ(i % 3, 0) << "an index outside the subset was returned";
}

TEST(FlannKdTree, AsksForMoreNeighboursThanPointsOrOnAnEmptyCloud)
{
  Cloud::Ptr three(new Cloud);
  three->push_back(pcl::PointXYZ(0, 0, 0));
  three->push_back(pcl::PointXYZ(1, 0, 0));
  three->push_back(pcl::PointXYZ(0, 2, 0));
  pcl_ls3d::search::FlannKdTree<pcl::PointXYZ> ours;
  ours.setInputCloud(three);
  pcl::Indices found;
  std::vector<float> d;
  EXPECT_EQ(ours.nearestKSearch(pcl::PointXYZ(0.9f, 0, 0), 10, found, d), 3);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0], 1);
  EXPECT_EQ(found[2], 2);
  EXPECT_EQ(ours.nearestKSearch(pcl::PointXYZ(0.9f, 0, 0), 0, found, d), 0);
  const pcl::PointXYZ nan_query(std::numeric_limits<float>::quiet_NaN(), 0, 0);
  EXPECT_EQ(ours.nearestKSearch(nan_query, 2, found, d), 0);

  ours.setInputCloud(Cloud::Ptr(new Cloud));
  EXPECT_EQ(ours.nearestKSearch(pcl::PointXYZ(0, 0, 0), 1, found, d), 0);
  EXPECT_TRUE(found.empty());
  EXPECT_EQ(ours.radiusSearch(pcl::PointXYZ(0, 0, 0), 5.0, found, d), 0);
}

TEST(FlannKdTree, SearchesLikeItsBaseWithACustomPointRepresentation)
{
  // Only z counts: the direct x, y, z path would be wrong, so the base class must answer.
  class HeightOnly : public pcl::PointRepresentation<pcl::PointXYZ>
  {
  public:
    HeightOnly()
    {
      nr_dimensions_ = 1;
    }
    void
    copyToFloatArray(const pcl::PointXYZ& p, float* out) const override
    {
      out[0] = p.z;
    }
  };
  const Cloud::Ptr cloud = randomCloudWithHoles(2000, 4);
  const auto representation = std::make_shared<const HeightOnly>();
  pcl::search::KdTree<pcl::PointXYZ> pcl_tree;
  pcl_tree.setPointRepresentation(representation);
  pcl_tree.setInputCloud(cloud);
  pcl_ls3d::search::FlannKdTree<pcl::PointXYZ> ours;
  ours.setPointRepresentation(representation);
  ours.setInputCloud(cloud);
  pcl::Indices a, b;
  std::vector<float> da, db;
  const pcl::PointXYZ query(50, -50, 1.0f);  // far away in x, y: only z may matter
  pcl_tree.nearestKSearch(query, 5, a, da);
  ours.nearestKSearch(query, 5, b, db);
  EXPECT_EQ(da, db);
  EXPECT_LT(db[0], 0.01f);
}
