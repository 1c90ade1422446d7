// Every tool that measures distances refuses inputs in degrees (or earth-centred) in one line,
// before any work. Before, pcl_ls3d_register matched a generated pair written in EPSG:4326
// (x, y in degrees, z in metres) to a 74 m "shift" and reported it CONVERGED and trustworthy.
#include <pcl_ls3d/io/cloud_io.h>
#include <pcl_ls3d/maps/coordinate_reference.h>
#include <pcl_ls3d/point_types.h>

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct ToolRun
{
  int code = -1;
  std::string err;
};

ToolRun
runTool(const std::string& tool, const std::string& args, const fs::path& dir)
{
  const fs::path err = dir / "err.txt";
  const std::string cmd = (fs::path(PCL_LS3D_TOOL_DIR) / tool).string() + " " + args +
                          " > /dev/null 2> " + err.string();
  const int status = std::system(cmd.c_str());
  std::ifstream f(err);
  std::stringstream ss;
  ss << f.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

/// A wavy 30 x 30 patch of 1 m spacing, x and y divided by \a per_unit (degrees: 1e5 m).
void
writePatch(const fs::path& path, const std::string& crs, double per_unit, float dz)
{
  pcl::PointCloud<pcl_ls3d::PointLiDAR> c;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      c.push_back(pcl_ls3d::PointLiDAR(static_cast<float>(i / per_unit),
                                       static_cast<float>(j / per_unit),
                                       std::sin(0.3f * i) + std::cos(0.2f * j) + dz));
  pcl_ls3d::io::SaveOptions o;
  o.las_vlrs = {pcl_ls3d::maps::wktVlr(pcl_ls3d::maps::crsFromUserInput(crs))};
  o.las_scale = {0.001 / per_unit, 0.001 / per_unit, 0.001};
  std::string error;
  ASSERT_TRUE(pcl_ls3d::io::saveCloud(path.string(), c, Eigen::Vector3d(2.0, 48.0, 0.0), error, o))
      << error;
}

}  // namespace

TEST(ToolsRefuseDegrees, OneLineBeforeAnyWork)
{
  const fs::path dir = fs::temp_directory_path() / ("ls3d_degrees_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path a = dir / "a.las", b = dir / "b.las", out = dir / "out";
  writePatch(a, "EPSG:4326", 1e5, 0.0f);
  writePatch(b, "EPSG:4326", 1e5, 0.2f);
  const std::string pair = a.string() + " " + b.string();
  const std::string calls[][2] = {
      {"pcl_ls3d_register", pair + " -o " + (dir / "aligned.las").string()},
      {"pcl_ls3d_compare", pair},
      {"pcl_ls3d_deformation", pair + " -o " + (dir / "residuals.pcd").string()},
      {"pcl_ls3d_strip_adjust", pair + " -o " + out.string()},
      {"pcl_ls3d_segment", a.string() + " -o " + (dir / "seg.pcd").string()},
  };
  for (const auto& call : calls) {
    SCOPED_TRACE(call[0]);
    const ToolRun r = runTool(call[0], call[1], dir);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("is in degrees (WGS 84)"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
  }
  EXPECT_FALSE(fs::exists(dir / "aligned.las"));
  EXPECT_FALSE(fs::exists(dir / "seg.pcd"));
  EXPECT_FALSE(fs::exists(dir / "residuals.pcd"));
  // Earth-centred coordinates too; a projected CRS is read on.
  const fs::path ecef = dir / "ecef.las", c = dir / "c.las", d = dir / "d.las";
  writePatch(ecef, "EPSG:4978", 1.0, 0.2f);
  EXPECT_NE(runTool("pcl_ls3d_register", a.string() + " " + ecef.string(), dir)
                .err.find("'" + ecef.string() + "' is in earth-centred"),
            std::string::npos);
  writePatch(c, "EPSG:2154", 1.0, 0.0f);
  writePatch(d, "EPSG:2154", 1.0, 0.2f);
  EXPECT_EQ(runTool("pcl_ls3d_register", c.string() + " " + d.string(), dir).err.find("degrees"),
            std::string::npos);
  fs::remove_all(dir);
}
