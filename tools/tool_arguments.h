#pragma once
/// \file tool_arguments.h
/// \brief Command-line checks shared by the pcl_ls3d_* tools. pcl::console's parse_argument()
///        silently ignores options it is not asked about, so a typo (-max_iters for -max_iter)
///        would run with defaults; every tool first validates argv against its option table.

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace tools {

/// \brief Splits argv[first..argc) into positional arguments. Options in `with_value` consume
///        the next word, `switches` stand alone, "-h"/"--help" are always accepted. Returns false
///        with a one-line reason on an unknown option or an option missing its value.
inline bool
splitArguments(int argc, char** argv, int first, const std::set<std::string>& with_value,
               const std::set<std::string>& switches, std::vector<std::string>& positional,
               std::string& why)
{
  for (int i = first; i < argc; ++i) {
    const std::string a = argv[i];
    if (with_value.count(a)) {
      if (i + 1 >= argc) {
        why = "Option " + a + " needs a value";
        return false;
      }
      ++i;
    }
    else if (switches.count(a) || a == "-h" || a == "--help")
      continue;
    else if (a.size() > 1 && a[0] == '-') {
      why = "Unknown option " + a + " (see -h)";
      return false;
    }
    else
      positional.push_back(a);
  }
  return true;
}

/// \brief Parses "a,b,c" into finite doubles; false on an empty list, an empty item, trailing
///        characters or a non-finite value.
inline bool
parseNumberList(const std::string& text, std::vector<double>& values)
{
  values.clear();
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v))
      return false;
    values.push_back(v);
  }
  return !values.empty();
}

}  // namespace tools
}  // namespace pcl_ls3d
