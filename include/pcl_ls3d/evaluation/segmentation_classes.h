#pragma once
/// \file segmentation_classes.h
/// \brief Reference class groups for segmentation evaluation: which ASPRS/LAS class codes make
///        "ground", "building", ... and which codes are left out of the evaluation. PCL-free.

#include <string>
#include <vector>

namespace pcl_ls3d {
namespace evaluation {

/// \brief The name of a LAS classification code for legends and reports: ASPRS LAS 1.4 R15
///        codes 0–18 ("ground", "low vegetation", ..., "building", "water", "bridge deck"; 8 and
///        12 as LAS 1.0–1.3 used them), "reserved" 19–63, "user-defined" 64–255 with the IGN
///        LiDAR HD meaning of 64–66 added (other producers use them otherwise: cars in synth).
std::string
lasClassName(int code);

/// \brief One evaluated class: a name and the reference label codes it gathers.
struct ClassGroup
{
  std::string name;
  std::vector<int> codes;
};

/// \brief ground {2}, building {6}, vegetation {3, 4, 5}, wire {14} (Wang et al. 2021 §4.1 scenes).
std::vector<ClassGroup>
defaultClassGroups();

/// \brief Codes left out of the evaluation by default: 0 (never classified) and 1 (unclassified).
std::vector<int>
defaultExcludedCodes();

/// \brief The codes actually left out: \a excluded minus any code named in a group (a group
///        that names code 1 scores it), ascending.
std::vector<int>
effectiveExcludedCodes(const std::vector<ClassGroup>& groups, const std::vector<int>& excluded);

/// \brief "codes 0/1 excluded", "code 0 excluded" or "no code excluded" for table headers.
std::string
describeExcludedCodes(const std::vector<ClassGroup>& groups, const std::vector<int>& excluded);

/// \brief Parses "ground=2,building=6,vegetation=3-5,wire=14,car=64" ('+' also joins codes:
///        "veg=3+4+5"). Names must be unique and non-empty, codes 0..255, no code in two groups.
/// \return false with a one-line reason in `error`
bool
parseClassGroups(const std::string& spec, std::vector<ClassGroup>& groups, std::string& error);

/// \brief Per code 0..255: index of its group, -1 for "other" (evaluated, in no group),
///        -2 for excluded. Codes outside 0..255 map to -2 (excluded) when looked up.
class ClassLookup
{
public:
  static constexpr int kOther = -1;
  static constexpr int kExcluded = -2;

  ClassLookup(const std::vector<ClassGroup>& groups, const std::vector<int>& excluded);
  int
  groupOf(int code) const
  {
    return (code < 0 || code > 255) ? kExcluded : table_[static_cast<std::size_t>(code)];
  }

private:
  std::vector<int> table_;
};

}  // namespace evaluation
}  // namespace pcl_ls3d
