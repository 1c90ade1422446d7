/// \file test_tool_options.cpp
/// \brief Issue 10 point 7, for every tool: numeric options are parsed strictly ("-params 6x",
///        "-max_iter abc" give one error line and a non-zero exit, never a silent default); an
///        output that cannot be written is refused before any input is read; pcl_ls3d_compare
///        keeps PCL's messages out of its table and fails when every method failed.

#include <pcl_ls3d/io/cloud_io.h>

#include "io/io_test_utils.h"
#include "io/tool_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace pcl_ls3d;
using pcl_ls3d_test::lineCount;
using pcl_ls3d_test::runTool;
using pcl_ls3d_test::TempDir;

namespace {

/// A 30 x 30 m wavy surface, 1 m grid, shifted by `dx` in x.
void
writeSurface(const std::string& path, double dx)
{
  pcl::PointCloud<PointLiDAR> cloud;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      cloud.push_back(PointLiDAR(static_cast<float>(i + dx), static_cast<float>(j),
                                 static_cast<float>(std::sin(i / 4.0) + std::cos(j / 5.0))));
  std::string error;
  ASSERT_TRUE(io::saveCloud(path, cloud, Eigen::Vector3d::Zero(), error)) << error;
}

class ToolOptions : public ::testing::Test
{
protected:
  void
  SetUp() override
  {
    writeSurface(dir_.file("a.pcd"), 0.0);
    writeSurface(dir_.file("far.pcd"), 1000.0);
    std::ofstream(dir_.file("not_a_folder")) << "x";
  }

  /// Runs and checks: non-zero exit, exactly one line on stderr naming `expect`, no "Loaded" on
  /// stdout (nothing was read before the refusal).
  void
  expectRefusal(const std::string& tool, const std::string& args, const std::string& expect)
  {
    SCOPED_TRACE(tool + " " + args);
    const auto r = runTool(tool, args, dir_.path.string());
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("Loaded"), std::string::npos) << r.out;
  }

  std::string
  file(const std::string& name) const
  {
    return dir_.file(name);
  }

  TempDir dir_{"ls3d_tool_options"};
};

}  // namespace

TEST_F(ToolOptions, NumericOptionsAreParsedStrictly)
{
  const std::string pair = file("a.pcd") + " " + file("a.pcd");
  const std::pair<std::string, std::string> register_cases[] = {{"-params 6x", "-params"},
                                                                {"-params abc", "-params"},
                                                                {"-max_iter abc", "-max_iter"},
                                                                {"-max_iter 2.5", "-max_iter"},
                                                                {"-K 6x", "-K"},
                                                                {"-thin abc", "-thin"},
                                                                {"-max_dist 1e999", "-max_dist"},
                                                                {"-guess 1x", "-guess"},
                                                                {"-guess -1", "-guess must be > 0"},
                                                                {"-max_dist -1", "-max_dist must be > 0"},
                                                                {"-params 7 -params 6", "given twice"}};
  for (const auto& [args, expect] : register_cases)
    expectRefusal("pcl_ls3d_register", pair + " " + args, expect);
  for (const auto& [args, expect] :
       std::vector<std::pair<std::string, std::string>>{{"-max_corr abc", "-max_corr"},
                                                        {"-iter 3x", "-iter"},
                                                        {"-ndt_res nan", "-ndt_res"},
                                                        {"-thinning -1", "-thinning"},
                                                        {"-gicp_grad x", "-gicp_grad"}})
    expectRefusal("pcl_ls3d_compare", pair + " " + args, expect);
  for (const auto& [args, expect] :
       std::vector<std::pair<std::string, std::string>>{{"-Nt abc", "-Nt"},
                                                        {"-threads 2x", "-threads"},
                                                        {"-eval_min_size 1x", "-eval_min_size"},
                                                        {"-min_fragment abc", "-min_fragment"},
                                                        {"-k 10,x", "-k"}})
    expectRefusal("pcl_ls3d_segment", file("a.pcd") + " " + args, expect);
  const std::string convert = file("a.pcd") + " " + file("b.las") + " ";
  for (const auto& [args, expect] :
       std::vector<std::pair<std::string, std::string>>{{"-las_format 3x", "-las_format"},
                                                        {"-las_scale abc", "-las_scale"},
                                                        {"-xyz_decimals 99", "-xyz_decimals"},
                                                        {"-origin 1,2,3x", "-origin"},
                                                        {"-classes 2,x", "-classes"},
                                                        {"-las_version 1.9", "-las_version"}})
    expectRefusal("pcl_ls3d_convert", convert + args, expect);
  for (const auto& [args, expect] : std::vector<std::pair<std::string, std::string>>{
           {"pair -seed 1x", "-seed"}, {"pair -overlap 0.5x", "-overlap"}, {"scene -trees abc", "-trees"}})
    expectRefusal("pcl_ls3d_synth", args + " -o " + file("synth"), expect);
  // Exit 1 as every tool's refusal (a return of -1 from main was exit 255).
  EXPECT_EQ(runTool("pcl_ls3d_synth", "pair -seed 1x -o " + file("synth"), dir_.path.string()).code, 1);
  for (const auto& [args, expect] :
       std::vector<std::pair<std::string, std::string>>{{"-max_iter abc", "-max_iter"},
                                                        {"-max_obs 6x", "-max_obs"},
                                                        {"-spacing x", "-spacing"},
                                                        {"-max_dist 1e999", "-max_dist"},
                                                        {"-min_area 2m", "-min_area"}})
    expectRefusal("pcl_ls3d_strip_adjust", pair + " " + args + " -o " + file("strips"), expect);
  expectRefusal("pcl_ls3d_strip_adjust", "match -work " + file("work") + " -job 1x", "-job");
  expectRefusal("pcl_ls3d_strip_adjust", "apply -work " + file("work") + " -unit -1", "-unit");
}

// Unwritable outputs (a missing folder, a file where the folder should be) are refused before
// the inputs are read: no "Loaded" line, one error naming the output.
TEST_F(ToolOptions, UnwritableOutputsAreRefusedBeforeAnyWork)
{
  const std::string a = file("a.pcd"), missing = file("missing/x"), under_file = file("not_a_folder/x");
  expectRefusal("pcl_ls3d_register", a + " " + a + " -o " + missing + ".pcd", "does not exist");
  expectRefusal("pcl_ls3d_register", a + " " + a + " -json " + under_file + ".json", "is not a folder");
  expectRefusal("pcl_ls3d_compare", a + " " + a + " -json " + missing + ".json", "does not exist");
  expectRefusal("pcl_ls3d_segment", a + " -o " + under_file + ".pcd", "is not a folder");
  expectRefusal("pcl_ls3d_segment", a + " -json " + missing + ".json", "does not exist");
  expectRefusal("pcl_ls3d_convert", a + " " + missing + ".las", "does not exist");
  expectRefusal("pcl_ls3d_convert", a + " -split_strips " + under_file, "is not a folder");
  expectRefusal("pcl_ls3d_synth", "pair -o " + under_file, "is not a folder");
  expectRefusal("pcl_ls3d_register", a + " " + a + " -o " + a, "is the input file");
  expectRefusal("pcl_ls3d_compare", a + " " + a + " -json " + dir_.path.string(), "is a folder");
}

// Two clouds 1 km apart: every method fails. PCL's own warnings stay out of the output (the
// table says "failed"), and the exit status is non-zero with one error line.
TEST_F(ToolOptions, CompareFailsWhenEveryMethodFailed)
{
  const auto r = runTool("pcl_ls3d_compare",
                         file("a.pcd") + " " + file("far.pcd") + " -methods icp,gicp,ls3d-lnd " +
                             "-max_corr 1 -json " + file("compare.json"),
                         dir_.path.string());
  EXPECT_NE(r.code, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("every method failed"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("[pcl::"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("[pcl::"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("failed"), std::string::npos) << r.out;
  EXPECT_TRUE(std::ifstream(file("compare.json")).good());  // the report is still written
  // The same clouds onto themselves: at least one method works, exit 0.
  const auto ok =
      runTool("pcl_ls3d_compare", file("a.pcd") + " " + file("a.pcd") + " -methods icp", dir_.path.string());
  EXPECT_EQ(ok.code, 0) << ok.out << ok.err;
}
