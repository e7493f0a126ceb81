#include "is_graphs/agraph/ifc_conversion.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>

#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/common/run_process.h"

namespace is_graphs {
namespace agraph {
namespace {

namespace fs = std::filesystem;

std::string Trimmed(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r\n") - begin + 1);
}

std::string LastLine(const std::string& text) {
  const std::string trimmed = Trimmed(text);
  const size_t newline = trimmed.find_last_of('\n');
  return Trimmed(newline == std::string::npos ? trimmed : trimmed.substr(newline + 1));
}

std::string Lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

std::string DefaultCacheDir() {
  const char* ros_home = std::getenv("ROS_HOME");
  if (ros_home != nullptr && *ros_home != '\0') return std::string(ros_home) + "/is_graphs/cache";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return std::string(home) + "/.ros/is_graphs/cache";
  return "/tmp/is_graphs/cache";
}

std::string IfcConversionConfig::Validate() const {
  if (python.empty()) return "python must name a Python interpreter";
  if (converter.empty()) return "converter must name the IFC converter script";
  return "";
}

Result<std::string> ConvertIfc(const IfcConversionConfig& config, const std::string& ifc_path) {
  using R = Result<std::string>;
  const std::string invalid = config.Validate();
  if (!invalid.empty()) return R::Error("IFC conversion: " + invalid);
  std::error_code ec;
  const fs::file_type type = fs::status(ifc_path, ec).type();
  if (type == fs::file_type::not_found) return R::Error(ifc_path + ": no such IFC file");
  if (type == fs::file_type::directory) {
    return R::Error("BIM path is a directory, not an IFC file: " + ifc_path);
  }
  // Anything else (unreadable, not a regular file, damaged) the converter names on stderr.
  if (config.python.find('/') != std::string::npos && access(config.python.c_str(), X_OK) != 0) {
    return R::Error("IFC conversion of " + ifc_path + ": Python interpreter '" + config.python +
                    "' not found or not executable (run `make setup` to create the venv, or "
                    "set the python to use)");
  }
  if (!fs::is_regular_file(config.converter, ec)) {
    return R::Error("IFC conversion of " + ifc_path + ": converter script '" + config.converter +
                    "' not found");
  }

  const std::string cache_dir = config.cache_dir.empty() ? DefaultCacheDir() : config.cache_dir;
  const std::vector<std::string> argv = {config.python, config.converter, ifc_path,
                                         "--cache-dir", cache_dir,        "--quiet"};
  const ProcessOutput run = RunProcess(argv);
  if (!run.started) return R::Error("IFC conversion of " + ifc_path + ": " + run.error);
  if (run.exit_code != 0) {
    const std::string stderr_text = Trimmed(run.stderr_text);
    return R::Error("IFC conversion of " + ifc_path + " failed (exit code " +
                    std::to_string(run.exit_code) + ")" +
                    (stderr_text.empty() ? std::string(", no message") : ":\n" + stderr_text));
  }
  const std::string agraph_path = LastLine(run.stdout_text);
  if (agraph_path.empty()) {
    return R::Error("IFC conversion of " + ifc_path + ": the converter printed no output path");
  }
  if (!fs::is_regular_file(agraph_path, ec)) {
    return R::Error("IFC conversion of " + ifc_path + ": the converter's output '" + agraph_path +
                    "' does not exist");
  }
  return R::Ok(agraph_path);
}

Result<AGraph> LoadBim(const std::string& path, const IfcConversionConfig& config) {
  const std::string extension = Lowercase(fs::path(path).extension().string());
  if (extension == ".ifc") {
    const Result<std::string> converted = ConvertIfc(config, path);
    if (!converted.ok()) return Result<AGraph>::Error(converted.error());
    return LoadAGraph(converted.value());
  }
  if (extension == ".json") return LoadAGraph(path);
  return Result<AGraph>::Error(path + ": unknown BIM file extension '" +
                               (extension.empty() ? std::string("(none)") : extension) +
                               "' (expected .ifc or .agraph.json)");
}

}  // namespace agraph
}  // namespace is_graphs
