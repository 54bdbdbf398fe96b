#include "bouncer/workflow/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

extern char** environ;

namespace bouncer {

pid_t start_child(const std::vector<std::string>& argv, int out_fd, int err_fd, const std::string& cwd,
                  const std::vector<std::string>& extra_env) {
  if (argv.empty()) return -1;
  // Everything the child needs is built before fork: between fork and exec it only makes
  // system calls (async-signal-safe), as a child of a threaded process must.
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<char*> env;
  for (char** e = environ; e && *e; ++e) env.push_back(*e);
  for (const std::string& e : extra_env) env.push_back(const_cast<char*>(e.c_str()));
  env.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid != 0) return pid;  // the parent (or -1)
  if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0 || ::getppid() != parent) ::_exit(127);
  const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  if (null < 0) ::_exit(127);
  if (::dup2(null, 0) < 0) ::_exit(127);
  if (::dup2(out_fd >= 0 ? out_fd : null, 1) < 0) ::_exit(127);
  if (::dup2(err_fd >= 0 ? err_fd : null, 2) < 0) ::_exit(127);
  if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(127);
  ::execve(args[0], args.data(), env.data());
  ::_exit(127);
}

}  // namespace bouncer
