#include <pcl_ls3d/common/similarity_transform.h>
#include <pcl_ls3d/evaluation/comparison_report.h>
#include <pcl_ls3d/io/json_text.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace pcl_ls3d {
namespace evaluation {

namespace {

using nlohmann::json;

/// A number, or null when not finite (JSON has no NaN).
json
num(double v)
{
  return std::isfinite(v) ? json(v) : json(nullptr);
}

json
rows(const Eigen::Matrix4d& T)
{
  json out = json::array();
  for (int r = 0; r < 4; ++r)
    out.push_back({num(T(r, 0)), num(T(r, 1)), num(T(r, 2)), num(T(r, 3))});
  return out;
}

/// "%*.*f" or "-" for NaN, right aligned in `width`.
std::string
cell(double v, int width, int decimals)
{
  char buf[64];
  if (std::isfinite(v))
    std::snprintf(buf, sizeof(buf), "%*.*f", width, decimals, v);
  else
    std::snprintf(buf, sizeof(buf), "%*s", width, "-");
  return buf;
}

/// "%*.3g" or "-" for NaN: lengths in a unit whose size is not known (feet, "units").
std::string
significant(double v, int width)
{
  char buf[64];
  if (std::isfinite(v))
    std::snprintf(buf, sizeof(buf), "%*.3g", width, v);
  else
    std::snprintf(buf, sizeof(buf), "%*s", width, "-");
  return buf;
}

/// "name[unit]" as a column header.
std::string
header(const char* name, const std::string& unit)
{
  return std::string(name) + "[" + unit + "]";
}

}  // namespace

std::string
formatComparisonTable(const std::vector<RegistrationRun>& runs, bool with_truth, const std::string& unit)
{
  // Error lengths: mm for metres; another unit is printed as is, with 3 significant digits.
  const bool metres = unit == "m";
  const std::string small = metres ? "mm" : unit;
  const auto length = [metres](double v, int width) {
    return metres ? cell(v * 1e3, width, 2) : significant(v, width);
  };
  std::string out;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%-10s %5s %8s %8s %5s %-10s %5s %8s %8s", "method", "iter", "time[s]",
                "cpu[s]", "conv", "stop", "trust", header("RMS", unit).c_str(), header("s0", unit).c_str());
  out += buf;
  if (with_truth) {
    std::snprintf(buf, sizeof(buf), " %9s %9s %9s | %8s %8s %8s %8s %8s %8s %8s",
                  header("mean", small).c_str(), header("max", small).c_str(), header("bbox", small).c_str(),
                  header("tx", small).c_str(), header("ty", small).c_str(), header("tz", small).c_str(),
                  "phi[ur]", "om[ur]", "ka[ur]", "m[ppm]");
    out += buf;
  }
  out += "\n";
  for (const auto& r : runs) {
    std::snprintf(buf, sizeof(buf), "%-10s %5d %8.3f %8.3f %5s %-10.10s %5s", r.name.c_str(), r.iterations,
                  r.time_s, r.cpu_s, !r.ran ? "FAIL" : (r.converged ? "yes" : "no"),
                  r.stop.empty() ? "-" : r.stop.c_str(),
                  !r.quality_checked ? "-" : (r.pcl_converged ? "yes" : "no"));
    out += buf;
    out += " " + cell(r.rms, 8, 4) + " " + cell(r.sigma0, 8, 4);
    if (with_truth) {
      const bool ok = r.ran && r.error.valid;
      const double nan = std::nan("");
      out += " " + length(ok ? r.error.mean : nan, 9) + " " + length(ok ? r.error.max : nan, 9) + " " +
             length(ok ? r.error.max_bbox : nan, 9) + " |";
      for (int i = 0; i < 3; ++i)
        out += " " + length(ok ? r.error.parameters[i] : nan, 8);
      for (int i = 3; i < 7; ++i)  // angles [µrad], scale [ppm]
        out += " " + cell(ok ? r.error.parameters[i] * 1e6 : nan, 8, 2);
    }
    if (!r.ran)
      out += "  (" + r.message + ")";
    out += "\n";
  }
  return out;
}

std::string
comparisonJson(const std::vector<RegistrationRun>& runs, const ComparisonContext& c)
{
  json j;
  j["context"] = {{"source", c.source},
                  {"target", c.target},
                  {"origin", {c.origin.x(), c.origin.y(), c.origin.z()}},
                  {"source_points", c.source_points},
                  {"target_points", c.target_points},
                  {"has_truth", c.has_truth},
                  {"rms_max_distance", c.rms_max_distance},
                  {"pcl_settings", c.pcl_settings},
                  {"ls3d_settings", c.ls3d_settings},
                  {"unit", c.unit},
                  {"units", c.unit + ", s, rad; transformation maps source to target"}};
  if (c.heights.converts()) {
    j["context"]["heights"] = heightUnitsJson(c.heights);
    j["context"]["file_origin"] = {c.file_origin.x(), c.file_origin.y(), c.file_origin.z()};
  }
  json methods = json::array();
  for (const auto& r : runs) {
    // File coordinates: x_working = x_local + origin for both clouds, heights then in the files' units.
    const Eigen::Matrix4d global = c.heights.toFiles(localToGlobal(r.transformation, c.origin, c.origin));
    json m = {{"name", r.name},
              {"ran", r.ran},
              {"message", r.message},
              {"iterations", r.iterations},
              {"time_s", num(r.time_s)},
              {"normals_time_s", num(r.normals_time_s)},
              {"cpu_s", num(r.cpu_s)},
              {"converged", r.converged},
              {"hit_iteration_limit", r.hit_limit},
              {"stop", r.stop},
              {"pcl_has_converged", r.pcl_converged},
              {"rms", num(r.rms)},
              {"rms_points", r.rms_points},
              {"sigma0", num(r.sigma0)},
              {"transformation_local", rows(r.transformation)},
              {"transformation", rows(global)}};
    if (c.has_truth && r.error.valid) {
      const auto& names = similarityParameterNames();
      json p;
      for (int i = 0; i < 7; ++i)
        p[names[static_cast<std::size_t>(i)]] = num(r.error.parameters[i]);
      m["error"] = {{"points", r.error.points},
                    {"mean", num(r.error.mean)},
                    {"rms", num(r.error.rms)},
                    {"max", num(r.error.max)},
                    {"max_bbox", num(r.error.max_bbox)},
                    {"parameters", p},
                    {"parameters_frame", "common local frame (rotation about origin)"}};
    } else if (c.has_truth) {
      m["error"] = nullptr;  // no estimate to compare with the truth
    }
    methods.push_back(m);
  }
  j["methods"] = methods;
  return io::toJsonText(j, 2);
}

}  // namespace evaluation
}  // namespace pcl_ls3d
