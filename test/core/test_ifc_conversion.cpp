#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "converter_check.h"
#include "fixtures.h"
#include "is_graphs/agraph/ifc_conversion.h"

namespace is_graphs {
namespace agraph {
namespace {

namespace fs = std::filesystem;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A Python string literal (JSON's escapes are Python's).
std::string PyString(const std::string& text) { return nlohmann::json(text).dump(); }

// A stand-in converter (run with the system Python): records its arguments in
// <dir>/argv.txt, writes `stderr_text` to stderr and `stdout_text` to stdout, exits with `code`.
IfcConversionConfig FakeConverter(const std::string& dir, const std::string& stdout_text,
                                  const std::string& stderr_text, int code) {
  const std::string script = dir + "/fake_converter.py";
  testing::WriteFile(script,
                     "import sys\n"
                     "open(" +
                         PyString(dir + "/argv.txt") +
                         ", 'w').write("
                         "'\\n'.join(sys.argv[1:]))\n"
                         "sys.stderr.write(" +
                         PyString(stderr_text) +
                         ")\n"
                         "sys.stdout.write(" +
                         PyString(stdout_text) +
                         ")\n"
                         "sys.exit(" +
                         std::to_string(code) + ")\n");
  IfcConversionConfig config;
  config.python = "/usr/bin/python3";
  config.converter = script;
  config.cache_dir = dir + "/cache dir";
  return config;
}

// An (empty) file standing in for an IFC, so that ConvertIfc gets to run the converter.
std::string FakeIfc(const std::string& dir, const std::string& name = "my building.ifc") {
  const std::string path = dir + "/" + name;
  testing::WriteFile(path, "ISO-10303-21;\n");
  return path;
}

TEST(IfcConversion, RealConverterOnTheOfficeBuilding) {
  const std::string ifc = std::string(IS_GRAPHS_SOURCE_DIR) + "/bim/office.ifc";
  IfcConversionConfig config;
  if (!fs::exists(ifc)) GTEST_SKIP() << ifc << " is not there (make buildings writes it)";
  if (!fs::exists(config.converter)) GTEST_SKIP() << "no converter at " << config.converter;
  if (config.python.find('/') != std::string::npos && access(config.python.c_str(), X_OK) != 0) {
    GTEST_SKIP() << "no Python at " << config.python << " (make setup creates the venv)";
  }
  if (!testing::IfcConverterMissing().empty()) GTEST_SKIP() << testing::IfcConverterMissing();
  const std::string dir = testing::ScratchDir("ifc_conversion_real");
  config.cache_dir = dir + "/cache";
  const Result<std::string> converted = ConvertIfc(config, ifc);
  ASSERT_TRUE(converted.ok()) << converted.error();
  EXPECT_TRUE(fs::is_regular_file(converted.value()));
  EXPECT_TRUE(Contains(converted.value(), ".agraph.json")) << converted.value();

  // LoadBim converts (from the cache now) and loads; the extension is case-insensitive.
  const std::string upper = dir + "/OFFICE.IFC";
  fs::copy_file(ifc, upper);
  const Result<AGraph> graph = LoadBim(upper, config);
  ASSERT_TRUE(graph.ok()) << graph.error();
  EXPECT_FALSE(graph.value().rooms.empty());
  EXPECT_FALSE(graph.value().walls.empty());
  EXPECT_TRUE(graph.value().mesh.empty() || fs::exists(graph.value().mesh)) << graph.value().mesh;
}

TEST(IfcConversion, ArgumentsPassWithoutAShell) {
  const std::string dir = testing::ScratchDir("ifc_conversion_args");
  const std::string ifc = FakeIfc(dir);
  const IfcConversionConfig config =
      FakeConverter(dir, "summary line\n" + testing::TwoRoomsPath() + "\n", "a warning\n", 0);
  const Result<std::string> converted = ConvertIfc(config, ifc);
  ASSERT_TRUE(converted.ok()) << converted.error();
  EXPECT_EQ(converted.value(), testing::TwoRoomsPath());  // the last stdout line
  EXPECT_EQ(testing::ReadFile(dir + "/argv.txt"),
            ifc + "\n--cache-dir\n" + dir + "/cache dir\n--quiet");

  const Result<AGraph> graph = LoadBim(ifc, config);
  ASSERT_TRUE(graph.ok()) << graph.error();
  EXPECT_EQ(graph.value().building, "Two Rooms");
}

TEST(IfcConversion, ConverterFailureCarriesItsStderr) {
  const std::string dir = testing::ScratchDir("ifc_conversion_failure");
  const std::string ifc = FakeIfc(dir);
  const IfcConversionConfig config =
      FakeConverter(dir, "", "ifc_to_agraph: error: my building.ifc: IfcWall #12: no axis\n", 2);
  const Result<std::string> converted = ConvertIfc(config, ifc);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "exit code 2")) << converted.error();
  EXPECT_TRUE(Contains(converted.error(), "my building.ifc: IfcWall #12: no axis"))
      << converted.error();
  EXPECT_FALSE(LoadBim(ifc, config).ok());
}

TEST(IfcConversion, ConverterOutputMustExist) {
  const std::string dir = testing::ScratchDir("ifc_conversion_no_output");
  const std::string ifc = FakeIfc(dir);
  Result<std::string> converted = ConvertIfc(FakeConverter(dir, "", "", 0), ifc);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "printed no output path")) << converted.error();
  converted = ConvertIfc(FakeConverter(dir, dir + "/gone.agraph.json\n", "", 0), ifc);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "gone.agraph.json' does not exist")) << converted.error();
}

TEST(IfcConversion, MissingPythonConverterOrIfc) {
  const std::string dir = testing::ScratchDir("ifc_conversion_missing");
  const std::string ifc = FakeIfc(dir);
  IfcConversionConfig config = FakeConverter(dir, "", "", 0);

  config.python = dir + "/no/python3";
  Result<std::string> converted = ConvertIfc(config, ifc);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "Python interpreter '" + config.python + "' not found"))
      << converted.error();

  config.python = "is-graphs-no-such-python";  // searched in PATH
  converted = ConvertIfc(config, ifc);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "cannot run is-graphs-no-such-python"))
      << converted.error();

  config.python = "/usr/bin/python3";
  config.converter = dir + "/no_converter.py";
  converted = ConvertIfc(config, ifc);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "converter script '" + config.converter + "' not found"))
      << converted.error();

  converted = ConvertIfc(config, dir + "/absent.ifc");
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "absent.ifc: no such IFC file")) << converted.error();

  converted = ConvertIfc(config, dir);
  ASSERT_FALSE(converted.ok());
  EXPECT_TRUE(Contains(converted.error(), "BIM path is a directory, not an IFC file: " + dir))
      << converted.error();
}

TEST(IfcConversion, LoadBimByExtension) {
  Result<AGraph> graph = LoadBim("building.txt");
  ASSERT_FALSE(graph.ok());
  EXPECT_TRUE(Contains(graph.error(), "building.txt: unknown BIM file extension '.txt'"))
      << graph.error();
  graph = LoadBim("building");
  ASSERT_FALSE(graph.ok());
  EXPECT_TRUE(Contains(graph.error(), "'(none)'")) << graph.error();

  graph = LoadBim(testing::TwoRoomsPath());  // .json: loaded directly
  ASSERT_TRUE(graph.ok()) << graph.error();
  EXPECT_EQ(graph.value().rooms.size(), 2u);
}

// A robot without IfcOpenShell (Ubuntu 20.04's Python 3.8 has no wheel): an .agraph.json
// converted on another machine loads with no Python at all.
TEST(IfcConversion, AGraphFileNeedsNoPython) {
  IfcConversionConfig config;
  config.python = "/nonexistent/python3";
  config.converter = "/nonexistent/ifc_to_agraph.py";
  const Result<AGraph> graph = LoadBim(testing::TwoRoomsPath(), config);
  ASSERT_TRUE(graph.ok()) << graph.error();
  EXPECT_EQ(graph.value().rooms.size(), 2u);
  // ... while an IFC with the same configuration says which interpreter is missing.
  const std::string office = std::string(IS_GRAPHS_SOURCE_DIR) + "/bim/office.ifc";
  const Result<AGraph> ifc = LoadBim(office, config);
  ASSERT_FALSE(ifc.ok());
  EXPECT_TRUE(Contains(ifc.error(), "/nonexistent/python3")) << ifc.error();
}

TEST(IfcConversion, ConfigValidate) {
  EXPECT_EQ(IfcConversionConfig().Validate(), "");
  IfcConversionConfig config;
  config.python.clear();
  EXPECT_TRUE(Contains(config.Validate(), "python"));
  EXPECT_FALSE(DefaultCacheDir().empty());
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
