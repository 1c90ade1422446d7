#include <pcl_ls3d/evaluation/segmentation_classes.h>

#include <algorithm>
#include <set>
#include <sstream>

namespace pcl_ls3d {
namespace evaluation {

namespace {
bool
parseCode(const std::string& s, int& code)
{
  if (s.empty() || s.size() > 3 || !std::all_of(s.begin(), s.end(), ::isdigit))
    return false;
  code = std::stoi(s);
  return code <= 255;
}

/// "3-5" or "2" or "3+4+5" -> codes.
bool
parseCodes(const std::string& s, std::vector<int>& codes)
{
  std::stringstream ss(s);
  std::string part;
  while (std::getline(ss, part, '+')) {
    const auto dash = part.find('-');
    int a = 0, b = 0;
    if (dash == std::string::npos) {
      if (!parseCode(part, a))
        return false;
      b = a;
    } else if (!parseCode(part.substr(0, dash), a) || !parseCode(part.substr(dash + 1), b) || b < a)
      return false;
    for (int c = a; c <= b; ++c)
      codes.push_back(c);
  }
  return !codes.empty();
}
}  // namespace

std::string
lasClassName(int code)
{
  static const char* const kAsprs[] = {"never classified",
                                       "unclassified",
                                       "ground",
                                       "low vegetation",
                                       "medium vegetation",
                                       "high vegetation",
                                       "building",
                                       "low point (noise)",
                                       "model key point (LAS 1.0–1.3)",
                                       "water",
                                       "rail",
                                       "road surface",
                                       "overlap (LAS 1.0–1.3)",
                                       "wire guard",
                                       "wire",
                                       "transmission tower",
                                       "wire connector",
                                       "bridge deck",
                                       "high noise"};
  if (code >= 0 && code < static_cast<int>(sizeof(kAsprs) / sizeof(kAsprs[0])))
    return kAsprs[code];
  switch (code) {  // IGN LiDAR HD, "sursol pérenne", "artefacts", "points virtuels"
  case 64:
    return "user-defined (IGN: permanent structure)";
  case 65:
    return "user-defined (IGN: artefact)";
  case 66:
    return "user-defined (IGN: virtual point)";
  default:
    return code >= 64 && code <= 255 ? "user-defined" : "reserved";
  }
}

std::vector<ClassGroup>
defaultClassGroups()
{
  return {{"ground", {2}}, {"building", {6}}, {"vegetation", {3, 4, 5}}, {"wire", {14}}};
}

std::vector<int>
defaultExcludedCodes()
{
  return {0, 1};
}

std::vector<int>
effectiveExcludedCodes(const std::vector<ClassGroup>& groups, const std::vector<int>& excluded)
{
  std::set<int> out(excluded.begin(), excluded.end());
  for (const auto& g : groups)
    for (int c : g.codes)
      out.erase(c);
  return {out.begin(), out.end()};
}

std::string
describeExcludedCodes(const std::vector<ClassGroup>& groups, const std::vector<int>& excluded)
{
  const std::vector<int> codes = effectiveExcludedCodes(groups, excluded);
  if (codes.empty())
    return "no code excluded";
  std::string list;
  for (int c : codes)
    list += (list.empty() ? "" : "/") + std::to_string(c);
  return (codes.size() == 1 ? "code " : "codes ") + list + " excluded";
}

bool
parseClassGroups(const std::string& spec, std::vector<ClassGroup>& groups, std::string& error)
{
  std::vector<ClassGroup> out;
  std::set<std::string> names;
  std::set<int> used;
  std::stringstream ss(spec);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    ClassGroup g;
    if (eq == std::string::npos || eq == 0 || !parseCodes(item.substr(eq + 1), g.codes)) {
      error = "bad class group '" + item + "' (expected name=codes, e.g. vegetation=3-5)";
      return false;
    }
    g.name = item.substr(0, eq);
    if (!names.insert(g.name).second) {
      error = "class group '" + g.name + "' given twice";
      return false;
    }
    for (int c : g.codes)
      if (!used.insert(c).second) {
        error = "class code " + std::to_string(c) + " is in two groups";
        return false;
      }
    out.push_back(g);
  }
  if (out.empty()) {
    error = "empty class group list";
    return false;
  }
  groups = out;
  return true;
}

ClassLookup::ClassLookup(const std::vector<ClassGroup>& groups, const std::vector<int>& excluded)
    : table_(256, kOther)
{
  for (int c : excluded)
    if (c >= 0 && c <= 255)
      table_[static_cast<std::size_t>(c)] = kExcluded;
  // A code named in a group is evaluated even if it is also in `excluded`.
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (int c : groups[g].codes)
      if (c >= 0 && c <= 255)
        table_[static_cast<std::size_t>(c)] = static_cast<int>(g);
}

}  // namespace evaluation
}  // namespace pcl_ls3d
