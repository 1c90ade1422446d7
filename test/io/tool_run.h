#pragma once
/// \file tool_run.h
/// \brief Runs a built pcl_ls3d_* tool (PCL_LS3D_TOOL_DIR) with a shell command line and keeps
///        its exit code, stdout and stderr (apart, or interleaved as in a log): the one runner of
///        every tool test.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pcl_ls3d_test {

struct ToolRun
{
  int code = -1;
  std::string out, err;
};

inline std::string
slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string
toolPath(const std::string& tool)
{
  return std::string(PCL_LS3D_TOOL_DIR) + "/" + tool;
}

/// `tool args > scratch/out 2> scratch/err`; args are passed to the shell as written.
inline ToolRun
runTool(const std::string& tool, const std::string& args, const std::string& scratch)
{
  const std::string out = scratch + "/tool_stdout.txt", err = scratch + "/tool_stderr.txt";
  const int status = std::system((toolPath(tool) + " " + args + " > '" + out + "' 2> '" + err + "'").c_str());
  ToolRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// `tool args > scratch/out 2>&1`: stdout and stderr interleaved in r.out as a log shows them
/// (r.err stays empty).
inline ToolRun
runToolMerged(const std::string& tool, const std::string& args, const std::string& scratch)
{
  const std::string out = scratch + "/tool_output.txt";
  const int status = std::system((toolPath(tool) + " " + args + " > '" + out + "' 2>&1").c_str());
  ToolRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  return r;
}

/// Non-empty lines of `text`.
inline std::size_t
lineCount(const std::string& text)
{
  std::size_t n = 0;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    n += !line.empty();
  return n;
}

}  // namespace pcl_ls3d_test
