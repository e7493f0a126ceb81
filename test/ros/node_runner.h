#pragma once
// Runs a real node binary against the rostest's roscore and captures its exit code and output
// (stdout and stderr). Each call gets its own node name, so private parameters set on the
// command line of one run never leak into another.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>
#include <utility>

namespace is_graphs {
namespace testing_support {

inline std::pair<int, std::string> RunNode(const std::string& binary, const std::string& name,
                                           const std::string& args) {
  static int run = 0;
  const std::string cmd =
      binary + " __name:=" + name + "_" + std::to_string(run++) + " " + args + " 2>&1";
  std::string output;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace testing_support
}  // namespace is_graphs
