#pragma once

#include <string>
#include <vector>

namespace is_graphs {

struct ProcessOutput {
  bool started{false};  // false: could not run (error says why)
  int exit_code{-1};    // the exit status; 128 + signal when killed by a signal
  std::string stdout_text;
  std::string stderr_text;
  std::string error;  // why it could not be started
};

/// Runs argv[0] (searched in PATH when it has no '/') with the arguments argv[1..], without a
/// shell (so no quoting issues), stdin from /dev/null, and captures stdout and stderr
/// separately. Blocks until the process exits.
ProcessOutput RunProcess(const std::vector<std::string>& argv);

}  // namespace is_graphs
