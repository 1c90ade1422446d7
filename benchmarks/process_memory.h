#pragma once
// Memory figures of the benchmarks that run each size in a fresh child process: a
// /proc/self/status field, a resettable high-water mark, and the child itself (this executable
// re-executed) with its RESULT line and its peak resident set from wait4().
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

namespace bench_process {

/// A /proc/self/status field in kB (VmHWM, VmRSS), −1 when absent.
inline long
statusKb(const std::string& key)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size() + 1, key + ":") == 0)
      return std::stol(line.substr(key.size() + 1));
  return -1;
}

/// Resets VmHWM to the current RSS (Linux >= 4.0); false when not permitted.
inline bool
resetPeak()
{
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  return static_cast<bool>(out);
}

/// What a child printed after "RESULT " and its peak resident set (ru_maxrss).
struct ChildResult
{
  bool ok = false;  ///< a RESULT line and exit status 0
  std::string line;
  long maxrss_kb = 0;
};

/// Runs this executable again with `args` (args[0] is its argv[0]) and collects its RESULT line.
inline ChildResult
runChild(const std::vector<std::string>& args)
{
  ChildResult r;
  int fd[2];
  if (pipe(fd) != 0)
    return r;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], STDOUT_FILENO);
    close(fd[0]);
    close(fd[1]);
    std::vector<char*> argv;
    for (const auto& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  close(fd[1]);
  std::string out;
  char buf[4096];
  ssize_t k;
  while ((k = read(fd[0], buf, sizeof(buf))) > 0)
    out.append(buf, static_cast<std::size_t>(k));
  close(fd[0]);
  int status = 0;
  struct rusage ru
  {};
  wait4(pid, &status, 0, &ru);
  r.maxrss_kb = ru.ru_maxrss;
  const auto pos = out.find("RESULT ");
  if (pos != std::string::npos) {
    r.line = out.substr(pos + 7, out.find('\n', pos) - pos - 7);
    r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }
  return r;
}

}  // namespace bench_process
