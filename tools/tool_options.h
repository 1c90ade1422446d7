#pragma once
/// \file tool_options.h
/// \brief Command-line checks shared by the pcl_ls3d_* tools (the CRS policy of the inputs is the
///        library's: io/cloud_pair.h).
///
/// - splitArguments(): pcl::console's parse_argument() silently ignores options it is not asked
///   about, so a typo (-max_iters for -max_iter) would run with defaults; every tool first
///   validates argv against its option table (unknown, repeated or value-less options refused).
/// - numberOption() / integerOption(): pcl::console's parse_argument() reads "6x" as 6 and "abc"
///   as 0; every numeric option goes through these strict parsers instead (the whole word must
///   be a finite number, integers must be whole and in range).
/// - checkOutputFile() / checkOutputFolder(): an output that cannot be written is refused before
///   any input is read, not after a long run (tried with a probe file, not read from permission
///   bits, which root and /proc make meaningless).
/// - parameterModelOption(): -params, one parser for every tool (each names the models it takes).

#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/io/cloud_io.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pcl_ls3d {
namespace tools {

/// \brief Splits argv[first..argc) into positional arguments. Options in `with_value` consume
///        the next word, `switches` stand alone, "-h"/"--help" are always accepted. Returns false
///        with a one-line reason on an unknown or repeated option, or an option missing its value.
inline bool
splitArguments(int argc, char** argv, int first, const std::set<std::string>& with_value,
               const std::set<std::string>& switches, std::vector<std::string>& positional, std::string& why)
{
  std::set<std::string> seen;
  for (int i = first; i < argc; ++i) {
    const std::string a = argv[i];
    const bool option = with_value.count(a) || switches.count(a);
    if (option && !seen.insert(a).second) {
      why = "Option " + a + " is given twice";
      return false;
    }
    if (with_value.count(a)) {
      if (i + 1 >= argc) {
        why = "Option " + a + " needs a value";
        return false;
      }
      ++i;
    } else if (switches.count(a) || a == "-h" || a == "--help")
      continue;
    else if (a.size() > 1 && a[0] == '-') {
      why = "Unknown option " + a + " (see -h)";
      return false;
    } else
      positional.push_back(a);
  }
  return true;
}

/// \brief The whole of `text` as a finite number ("6x", "abc", "", "nan", "1e999" are refused).
inline bool
parseStrictDouble(const std::string& text, double& value)
{
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
    return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno == ERANGE || !std::isfinite(v))
    return false;
  value = v;
  return true;
}

/// \brief The value of option `name` (the word after it), or nullptr when it is not given.
inline const char*
optionValue(int argc, char** argv, const std::string& name)
{
  for (int i = 1; i + 1 < argc; ++i)
    if (name == argv[i])
      return argv[i + 1];
  return nullptr;
}

/// \brief Reads numeric option `name` into `value` when given; false with a one-line reason
///        when it is not a finite number in [lo, hi]. `value` is untouched when absent.
inline bool
numberOption(int argc, char** argv, const std::string& name, double& value, std::string& why,
             double lo = -std::numeric_limits<double>::max(), double hi = std::numeric_limits<double>::max())
{
  const char* text = optionValue(argc, argv, name);
  if (!text)
    return true;
  double v = 0.0;
  if (!parseStrictDouble(text, v) || v < lo || v > hi) {
    std::ostringstream s;
    s << name << " expects a number";
    const bool low = lo > -std::numeric_limits<double>::max(), high = hi < std::numeric_limits<double>::max();
    if (low && high)
      s << " in [" << lo << ", " << hi << "]";
    else if (low)  // no machine limits in a user's message
      s << " >= " << lo;
    else if (high)
      s << " <= " << hi;
    s << ", got '" << text << "'";
    why = s.str();
    return false;
  }
  value = v;
  return true;
}

/// \brief Integer version of numberOption(): whole numbers in [lo, hi] only ("6x", "6.5" refused).
template <typename Int>
inline bool
integerOption(int argc, char** argv, const std::string& name, Int& value, std::string& why, long long lo,
              long long hi)
{
  const char* text = optionValue(argc, argv, name);
  if (!text)
    return true;
  double v = 0.0;
  if (!parseStrictDouble(text, v) || v != std::floor(v) || v < static_cast<double>(lo) ||
      v > static_cast<double>(hi)) {
    why = name + " expects an integer " +
          (hi >= 2147483647 ? ">= " + std::to_string(lo)
                            : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]") +
          ", got '" + text + "'";
    return false;
  }
  value = static_cast<Int>(v);
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
    double v = 0.0;
    if (!parseStrictDouble(item, v))
      return false;
    values.push_back(v);
  }
  return !values.empty() && text.back() != ',';
}

/// \brief -bounds "xmin,ymin,xmax,ymax" (2-D) or "xmin,ymin,xmax,ymax,zmin,zmax" (3-D), in file
///        coordinates, into a region box (io::Region); false with a one-line reason naming
///        `option` for another count, a non-finite number or a minimum above its maximum.
inline bool
parseBounds(const std::string& option, const std::string& text, pcl_ls3d::io::Region& region,
            std::string& why)
{
  std::vector<double> v;
  if (!parseNumberList(text, v) || (v.size() != 4 && v.size() != 6)) {
    why = option +
          " takes xmin,ymin,xmax,ymax or xmin,ymin,xmax,ymax,zmin,zmax (file coordinates), "
          "got '" +
          text + "'";
    return false;
  }
  region.use_z = v.size() == 6;
  const double zmin = region.use_z ? v[4] : 0.0, zmax = region.use_z ? v[5] : 0.0;
  if (v[0] > v[2] || v[1] > v[3] || zmin > zmax) {
    why = option + " '" + text + "': a minimum exceeds its maximum";
    return false;
  }
  region.box = Eigen::AlignedBox3d(Eigen::Vector3d(v[0], v[1], zmin), Eigen::Vector3d(v[2], v[3], zmax));
  return true;
}

/// \brief The region options of a tool that reads one cloud: -bounds (parseBounds) and -level N
///        (COPC octree levels 0..N only; needs -bounds). `region` is left empty without -bounds.
inline bool
regionOptions(int argc, char** argv, std::optional<pcl_ls3d::io::Region>& region, std::string& why)
{
  const char* bounds = optionValue(argc, argv, "-bounds");
  int level = -1;
  if (!integerOption(argc, argv, "-level", level, why, 0, 40))
    return false;
  if (!bounds) {
    if (level >= 0)
      return (why = "-level needs -bounds (the box to read the octree levels of)"), false;
    return true;
  }
  pcl_ls3d::io::Region r;
  if (!parseBounds("-bounds", bounds, r, why))
    return false;
  r.max_level = level;
  region = r;
  return true;
}

/// \brief "2,6" into LAS class codes (whole numbers 0–255); false with a one-line reason naming
///        `option`.
inline bool
parseClassList(const std::string& option, const std::string& text, std::set<std::uint8_t>& classes,
               std::string& why)
{
  std::vector<double> values;
  if (!parseNumberList(text, values)) {
    why = option + " expects a comma list of class codes, e.g. 2,6, got '" + text + "'";
    return false;
  }
  for (double v : values) {
    if (v < 0 || v > 255 || v != std::floor(v)) {
      why = option + ": '" + text + "' holds a value that is not a class code 0-255";
      return false;
    }
    classes.insert(static_cast<std::uint8_t>(v));
  }
  return true;
}

/// \brief Can a file be created at `path` (absent) or written (present)? Tried, not guessed
///        from permission bits (root passes every access() test, /proc refuses every file):
///        an absent file is created and removed again, a present one opened without truncation.
inline bool
probeWritable(const std::string& path, std::string& why)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool existed = fs::exists(path, ec);
  const int fd = existed ? ::open(path.c_str(), O_WRONLY | O_APPEND)
                         : ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    why = "cannot write " + path + ": " + std::strerror(errno);
    return false;
  }
  ::close(fd);
  if (!existed)
    fs::remove(path, ec);
  return true;
}

/// \brief Refuses an output file before any work: it names one of `inputs`, exists without
///        `overwrite`, is a folder or another non-regular file (/dev/null) or a symbolic link to
///        nothing (no file is created through it), has a cloud format
///        saveCloud() cannot write (when `cloud`), or cannot be created or written (tried: see
///        probeWritable). Changes nothing. An empty path passes.
inline bool
checkOutputFile(const std::string& path, const std::vector<std::string>& inputs, bool overwrite,
                std::string& why, bool cloud = false)
{
  namespace fs = std::filesystem;
  if (path.empty())
    return true;
  for (const auto& in : inputs)
    if (!in.empty() && io::isSameFile(path, in)) {
      why = "output " + path + " is the input file " + in + "; refusing to overwrite it";
      return false;
    }
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  if (cloud && !io::canSaveFormat(path, why))
    why = path + ": " + why;
  else if (fs::is_symlink(fs::symlink_status(path, ec)) && !fs::exists(path, ec))
    why = "output " + path + " is a symbolic link to the missing " + fs::read_symlink(path, ec).string() +
          "; remove the link or name another output";
  else if (fs::is_directory(path, ec))
    why = "output " + path + " is a folder, not a file";
  else if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    why = "output " + path + " is not a regular file";
  else if (fs::exists(path, ec) && !overwrite)
    why = "output " + path + " exists already (use -overwrite to replace it)";
  else if (!fs::exists(parent, ec))
    why = "cannot write " + path + ": folder " + parent.string() + " does not exist";
  else if (!fs::is_directory(parent, ec))
    why = "cannot write " + path + ": " + parent.string() + " is not a folder";
  else
    probeWritable(path, why);
  return why.empty();
}

/// \brief Refuses an output folder that exists but is not a folder or cannot take a new file, or
///        that cannot be created (its nearest existing ancestor cannot take one: tried with a
///        probe file, removed again). Creates nothing that stays.
inline bool
checkOutputFolder(const std::string& dir, std::string& why)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path p = fs::absolute(dir, ec);
  while (!p.empty() && !fs::exists(p, ec) && p != p.parent_path())
    p = p.parent_path();
  std::string probe_why;
  if (!fs::is_directory(p, ec))
    why = "cannot create or write the folder " + dir + ": " + p.string() + " is not a folder";
  else if (!probeWritable((p / (".pcl_ls3d_probe_" + std::to_string(::getpid()))).string(), probe_why))
    why = "cannot create or write the folder " + dir + ": no file can be created in " + p.string() + " (" +
          probe_why.substr(probe_why.rfind(": ") + 2) + ")";
  return why.empty();
}

/// \brief -params, parsed the one way every tool parses it: one of \a accepted (texts that
///        parseParameterModel() knows, in the order the tool's help lists them). \a model is
///        untouched when the option is absent; false with a one-line reason otherwise.
inline bool
parameterModelOption(int argc, char** argv, const std::vector<std::string>& accepted, ParameterModel& model,
                     std::string& why)
{
  const char* text = optionValue(argc, argv, "-params");
  if (!text)
    return true;
  if (std::find(accepted.begin(), accepted.end(), text) != accepted.end() && parseParameterModel(text, model))
    return true;
  why = "-params expects ";
  for (std::size_t i = 0; i < accepted.size(); ++i)
    why += (i == 0 ? "" : i + 1 == accepted.size() ? " or " : ", ") + accepted[i];
  why += std::string(", got '") + text + "'";
  return false;
}

}  // namespace tools
}  // namespace pcl_ls3d
