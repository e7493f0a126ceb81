#include "run_marker.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace is_graphs {
namespace ros_run {
namespace {

std::string StateDir() {
  if (const char* home = std::getenv("ROS_HOME"); home && *home)
    return std::string(home) + "/is_graphs";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/.ros/is_graphs";
  return "/tmp/is_graphs";
}

}  // namespace

RunMarker::RunMarker(const std::string& name, const std::string& run_id) : run_id_(run_id) {
  std::string file = name;
  for (char& c : file)
    if (c == '/') c = '_';
  path_ = StateDir() + "/" + file + ".run";
  std::ifstream in(path_);
  std::string first;
  if (!run_id_.empty() && std::getline(in, first) && first == "run_id: " + run_id_) {
    std::ostringstream rest;
    rest << in.rdbuf();
    previous_ = rest.str();
    while (!previous_.empty() && previous_.back() == '\n') previous_.pop_back();
  }
}

std::string RunMarker::Write(const std::string& summary) const {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path(), ec);
  if (ec)
    return "cannot create " + std::filesystem::path(path_).parent_path().string() + ": " +
           ec.message();
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream out(tmp);
    out << "run_id: " << run_id_ << "\n" << summary << "\n";
    if (!out) return "cannot write " + tmp;
  }
  std::filesystem::rename(tmp, path_, ec);
  return ec ? "cannot rename " + tmp + ": " + ec.message() : "";
}

}  // namespace ros_run
}  // namespace is_graphs
