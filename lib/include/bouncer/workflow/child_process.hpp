// Child processes of reproduce and audit: this binary (or a proof program beside it) run on
// a command line that bouncer built itself, with its output on descriptors bouncer owns.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace bouncer {

// Starts argv[0] (a path: no PATH search) with stdin from /dev/null and stdout and stderr on
// `out_fd` and `err_fd` (-1: /dev/null), in the directory `cwd` (empty: this one), with
// `extra_env` ("NAME=VALUE") added to the environment. The child is sent SIGTERM when this
// process ends, however it ends (PR_SET_PDEATHSIG; checked against a parent that died while
// the child started), so that a reproduce or audit killed with SIGKILL leaves no
// computation running. Returns the child's pid, or -1.
pid_t start_child(const std::vector<std::string>& argv, int out_fd, int err_fd, const std::string& cwd = "",
                  const std::vector<std::string>& extra_env = {});

}  // namespace bouncer
