#pragma once
/// \file memory_probe.h
/// \brief Runs loadCloud() in a forked child and measures what it cost: the child resets its peak
///        resident set (/proc/self/clear_refs, "5"), notes its resident set, loads, and reports
///        its new peak (VmHWM) minus that base. Outside sanitizer
///        builds the child's address space is also capped (RLIMIT_AS), so even an allocation that
///        is never touched (and so never resident) fails loudly: std::bad_alloc is not caught by
///        the readers and kills the child, which the probe reports. Nothing is timed.

#include <pcl_ls3d/io/cloud_io.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#if defined(__SANITIZE_ADDRESS__)
#define PCL_LS3D_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PCL_LS3D_TEST_ASAN 1
#endif
#endif

namespace pcl_ls3d_test {

struct ProbeResult
{
  bool child_ok = false;    ///< the child ran to its end (no crash, no uncaught bad_alloc)
  bool loaded = false;      ///< loadCloud() returned true
  std::string error;        ///< its one-line reason otherwise
  long peak_growth_kb = 0;  ///< child's peak RSS during the load minus its RSS before [KiB]
};

/// A "Vm...:" value of /proc/self/status in KiB (0 when absent).
inline long
procStatusKb(const char* key)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, std::strlen(key), key) == 0)
      return std::atol(line.c_str() + std::strlen(key));
  return 0;
}

/// Loads `path` in a child whose address space may grow by at most `cap_mb` (not under ASan).
inline ProbeResult
probeLoad(const std::string& path, long cap_mb)
{
  ProbeResult r;
  int fds[2];
  if (::pipe(fds) != 0)
    return r;
  const long size_kb = procStatusKb("VmSize:");
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
#ifndef PCL_LS3D_TEST_ASAN
    const rlim_t cap = static_cast<rlim_t>(size_kb + cap_mb * 1024) * 1024;
    const struct rlimit limit = {cap, cap};
    ::setrlimit(RLIMIT_AS, &limit);
#endif
    std::ofstream("/proc/self/clear_refs") << "5";  // VmHWM := VmRSS
    const long base_kb = procStatusKb("VmRSS:");
    pcl::PointCloud<pcl_ls3d::PointLiDAR> cloud;
    pcl_ls3d::io::CloudInfo info;
    std::string error;
    const bool ok = pcl_ls3d::io::loadCloud(path, cloud, info, error);
    const long growth_kb = procStatusKb("VmHWM:") - base_kb;
    const std::string message = std::to_string(growth_kb) + " " + (ok ? "1" : "0") + error;
    if (::write(fds[1], message.data(), message.size()) < 0)
      ::_exit(2);
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[4096];
  ssize_t n;
  while ((n = ::read(fds[0], buffer, sizeof(buffer))) > 0)
    message.append(buffer, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) != pid)
    return r;
  const std::size_t space = message.find(' ');
  r.child_ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && space != std::string::npos &&
               space + 1 < message.size();
  if (!r.child_ok)
    return r;
  r.peak_growth_kb = std::atol(message.c_str());
  r.loaded = message[space + 1] == '1';
  r.error = message.substr(space + 2);
  return r;
}

}  // namespace pcl_ls3d_test
