#include <pcl_ls3d/evaluation/segmentation_report.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pcl_ls3d {
namespace evaluation {

namespace {
std::string
percent(double v)
{
  if (std::isnan(v))
    return "-";
  char buf[16];
  std::snprintf(buf, sizeof(buf), "%.1f", 100.0 * v);
  return buf;
}

std::string
pad(const std::string& s, std::size_t w)
{
  return s.size() >= w ? s : std::string(w - s.size(), ' ') + s;
}

/// The first evaluation that did not fail (its classes name the columns), or the first.
template <typename Evaluation>
const Evaluation&
columnSource(const std::vector<Evaluation>& evaluations)
{
  for (const auto& e : evaluations)
    if (e.failure.empty())
      return e;
  return evaluations.front();
}
}  // namespace

std::string
formatSegmentationTable(const std::vector<SegmentationEvaluation>& evaluations)
{
  if (evaluations.empty())
    return "";
  const auto& first = columnSource(evaluations).classes;
  std::vector<std::size_t> shown;
  for (std::size_t c = 0; c < first.size(); ++c) {
    bool any = false;
    for (const auto& e : evaluations)
      any |= c < e.classes.size() && (e.classes[c].reference_points > 0 || e.classes[c].predicted_points > 0);
    if (any)
      shown.push_back(c);
  }
  std::size_t wm = 6;
  for (const auto& e : evaluations)
    wm = std::max(wm, e.method.size());

  std::ostringstream os;
  os << std::string(wm - 6, ' ') << "method | segments |  time s |";
  for (std::size_t c : shown)
    os << ' ' << pad(first[c].name + " P/R/F1 %", 22) << " |";
  os << '\n' << std::string(wm, '-') << "-|----------|---------|";
  for (std::size_t i = 0; i < shown.size(); ++i)
    os << std::string(24, '-') << '|';
  os << '\n';
  for (const auto& e : evaluations) {
    char t[32];
    std::snprintf(t, sizeof(t), "%7.2f", e.seconds);
    os << pad(e.method, wm) << " | " << pad(std::to_string(e.segments), 8) << " | " << t << " |";
    if (!e.failure.empty()) {
      os << " failed: " << e.failure << '\n';
      continue;
    }
    for (std::size_t c : shown) {
      const ClassScores& s = e.classes[c];
      os << ' ' << pad(percent(s.precision) + " / " + percent(s.recall) + " / " + percent(s.f1), 22) << " |";
    }
    os << '\n';
  }
  return os.str();
}

namespace {
/// Indices of the classes that have objects in the first evaluation.
std::vector<std::size_t>
objectClassesShown(const std::vector<ObjectEvaluation>& evaluations)
{
  std::vector<std::size_t> shown;
  const auto& first = columnSource(evaluations).classes;
  for (std::size_t c = 0; c < first.size(); ++c)
    if (first[c].objects > 0)
      shown.push_back(c);
  return shown;
}

/// "method | segments |  time s |" header line, its rule and the width of the method column.
std::size_t
methodWidth(const std::vector<ObjectEvaluation>& evaluations)
{
  std::size_t wm = 6;
  for (const auto& e : evaluations)
    wm = std::max(wm, e.method.size());
  return wm;
}

std::string
fixed(double v, const char* format)
{
  if (std::isnan(v))
    return "-";
  char buf[32];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}
}  // namespace

std::string
formatObjectTable(const std::vector<ObjectEvaluation>& evaluations)
{
  if (evaluations.empty())
    return "";
  const auto shown = objectClassesShown(evaluations);
  const auto& first = columnSource(evaluations).classes;
  const std::size_t wm = methodWidth(evaluations);
  std::ostringstream os;
  os << std::string(wm - 6, ' ') << "method | segments |  time s |";
  for (std::size_t c : shown)
    os << ' ' << pad(first[c].name + " P/R/F1 %", 22) << " |";
  os << '\n' << std::string(wm, '-') << "-|----------|---------|";
  for (std::size_t i = 0; i < shown.size(); ++i)
    os << std::string(24, '-') << '|';
  os << '\n';
  for (const auto& e : evaluations) {
    os << pad(e.method, wm) << " | " << pad(std::to_string(e.segments), 8) << " | "
       << pad(fixed(e.seconds, "%.2f"), 7) << " |";
    if (!e.failure.empty()) {
      os << " failed: " << e.failure << '\n';
      continue;
    }
    for (std::size_t c : shown) {
      const ObjectClassScores& s = e.classes[c];
      os << ' ' << pad(percent(s.precision) + " / " + percent(s.recall) + " / " + percent(s.f1), 22) << " |";
    }
    os << '\n';
  }
  return os.str();
}

std::string
formatFragmentationTable(const std::vector<ObjectEvaluation>& evaluations, std::size_t min_points)
{
  if (evaluations.empty())
    return "";
  const auto shown = objectClassesShown(evaluations);
  const auto& first = columnSource(evaluations).classes;
  const std::size_t wm = methodWidth(evaluations);
  std::ostringstream os;
  os << std::string(wm - 6, ' ') << "method |";
  for (std::size_t c : shown)
    os << ' ' << pad(first[c].name + " rec/obj seg share", 26) << " |";
  os << '\n' << std::string(wm, '-') << "-|";
  for (std::size_t i = 0; i < shown.size(); ++i)
    os << std::string(28, '-') << '|';
  os << '\n';
  for (const auto& e : evaluations) {
    os << pad(e.method, wm) << " |";
    if (!e.failure.empty()) {
      os << " failed: " << e.failure << '\n';
      continue;
    }
    for (std::size_t c : shown) {
      const ObjectClassScores& s = e.classes[c];
      os << ' '
         << pad(std::to_string(s.recognised) + "/" + std::to_string(s.objects) + "  " +
                    fixed(s.median_valid_segments, "%.1f") + "  " + fixed(s.median_largest_share, "%.2f"),
                26)
         << " |";
    }
    os << '\n';
  }
  os << "(rec/obj: recognised / reference objects; seg, share: medians over the objects of at "
        "least "
     << min_points
     << " points of valid segments per object and of the largest valid segment's "
        "share of the object)\n";
  return os.str();
}

std::string
describeConfusion(const SegmentationEvaluation& e, double min_share)
{
  const std::size_t G = e.classes.size();
  auto colName = [&](std::size_t c) {
    return c < G ? e.classes[c].name : (c == G ? std::string("other") : std::string("none"));
  };
  std::ostringstream os;
  for (std::size_t r = 0; r <= G && r < e.confusion.size(); ++r) {
    std::size_t total = 0;
    for (std::size_t v : e.confusion[r])
      total += v;
    if (total == 0)
      continue;
    std::vector<std::size_t> cols(e.confusion[r].size());
    for (std::size_t c = 0; c < cols.size(); ++c)
      cols[c] = c;
    std::sort(cols.begin(), cols.end(),
              [&](std::size_t a, std::size_t b) { return e.confusion[r][a] > e.confusion[r][b]; });
    os << "  " << colName(r) << " (" << total << " pts) ->";
    for (std::size_t c : cols) {
      const double share = static_cast<double>(e.confusion[r][c]) / static_cast<double>(total);
      if (share < min_share || e.confusion[r][c] == 0)
        break;
      os << ' ' << percent(share) << "% " << colName(c) << ',';
    }
    os.seekp(-1, std::ios_base::end);
    os << '\n';
  }
  return os.str();
}

}  // namespace evaluation
}  // namespace pcl_ls3d
