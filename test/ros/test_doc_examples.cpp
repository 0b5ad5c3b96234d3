// The documentation can be taken at its word: every YAML block on a page is either run through the real
// costmap_tool (and exits 0 with no warning) or says why it cannot be; each plugin's page has such an
// example that loads the plugin; every `roslaunch costmap_layers FILE ARGS` line is dry-run through
// roslaunch; and every link, launch file and program the pages name exists (test/docs/check_links.py).
//
// Every ```yaml fence follows an HTML comment line (blank lines may come between):
//   <!-- example: costmap_tool [OPTIONS] -->   the block is a costmap's params YAML (--params)
//   <!-- example: zone_file -->                the block is a zone_server zone file (fed as a mask)
//   <!-- example: none REASON -->              not runnable on its own; REASON says why (required)
// OPTIONS are costmap_tool options; relative paths in them are the package's. Without --map the example
// runs on test/data/maps/turtlebot3_world.yaml.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>

#include "tool_runner.hpp"

using namespace costmap_layers_test;
namespace fs = std::filesystem;

namespace
{
/// The package's folder; COSTMAP_LAYERS_DOCS_ROOT points the test at a copy (to check documentation
/// before it replaces the committed one).
fs::path docsRoot()
{
  const char* root = std::getenv("COSTMAP_LAYERS_DOCS_ROOT");
  return (root != nullptr && *root != '\0') ? fs::path(root) : fs::path(COSTMAP_LAYERS_SOURCE_DIR);
}

struct Example
{
  std::string where;  ///< page:line of the fence (or of a marker without a fence)
  std::string kind;   ///< costmap_tool, zone_file, none; "" when the fence has no marker
  std::vector<std::string> options;
  std::string reason;  ///< for none: the rest of the marker
  std::string yaml;
  bool has_block = false;
};

/// README.md, CHANGELOG.rst and every docs/**/*.md, in a fixed order.
std::vector<fs::path> pages(const fs::path& root)
{
  std::vector<fs::path> result{root / "README.md"};
  std::vector<fs::path> docs;
  for (const auto& entry : fs::recursive_directory_iterator(root / "docs"))
    if (entry.is_regular_file() && entry.path().extension() == ".md") docs.push_back(entry.path());
  std::sort(docs.begin(), docs.end());
  result.insert(result.end(), docs.begin(), docs.end());
  result.push_back(root / "CHANGELOG.rst");
  return result;
}

std::vector<std::string> linesOf(const fs::path& page)
{
  std::istringstream in(readFile(page.string()));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

/// Every ```yaml block of one page with its marker, and every marker that no ```yaml block follows (so
/// that it fails rather than being skipped). Fences may be indented (a block inside a list item): the
/// block's lines lose the fence's indentation.
std::vector<Example> examplesOf(const fs::path& page, const fs::path& root)
{
  static const std::regex marker(R"(^\s*<!--\s*example:\s*(\S+)(.*?)-->\s*$)");
  static const std::regex fence(R"(^(\s*)(```|~~~)\s*([A-Za-z0-9_+-]*).*$)");
  const auto lines = linesOf(page);
  const std::string name = fs::relative(page, root).string();
  std::vector<Example> result;
  std::optional<Example> pending;  // a marker waiting for its block
  for (size_t i = 0; i < lines.size(); ++i)
  {
    std::smatch m;
    if (std::regex_match(lines[i], m, marker))
    {
      if (pending) result.push_back(*pending);
      Example ex;
      ex.where = name + ":" + std::to_string(i + 1);
      ex.kind = m[1];
      std::istringstream opts(m[2].str());
      for (std::string token; opts >> token;)
        ex.options.push_back(token);
      ex.reason = m[2].str();
      ex.reason.erase(0, ex.reason.find_first_not_of(" \t"));
      pending = ex;
      continue;
    }
    if (!std::regex_match(lines[i], m, fence))
    {
      // Anything but blank lines between a marker and its block detaches the marker.
      if (pending && lines[i].find_first_not_of(" \t") != std::string::npos)
      {
        result.push_back(*pending);
        pending.reset();
      }
      continue;
    }
    const std::string indent = m[1], ticks = m[2], language = m[3];
    // The block's body, up to the closing fence.
    std::string body;
    size_t j = i + 1;
    for (; j < lines.size(); ++j)
    {
      const std::string& l = lines[j];
      const auto first = l.find_first_not_of(" \t");
      if (first != std::string::npos && l.compare(first, ticks.size(), ticks) == 0 &&
          l.find_first_not_of(" \t`~", first) == std::string::npos)
        break;
      body += (l.compare(0, indent.size(), indent) == 0 ? l.substr(indent.size()) : l) + "\n";
    }
    if (language == "yaml" || language == "yml")
    {
      Example ex = pending ? *pending : Example{};
      if (!pending) ex.where = name + ":" + std::to_string(i + 1);
      ex.yaml = body;
      ex.has_block = true;
      result.push_back(ex);
    }
    else if (pending)
    {
      result.push_back(*pending);  // a marker before a block that is not YAML
    }
    pending.reset();
    i = j;
  }
  if (pending) result.push_back(*pending);
  return result;
}

std::vector<Example> allExamples()
{
  const fs::path root = docsRoot();
  std::vector<Example> all;
  for (const auto& page : pages(root))
  {
    if (page.extension() != ".md") continue;
    const auto found = examplesOf(page, root);
    all.insert(all.end(), found.begin(), found.end());
  }
  return all;
}

/// A relative path in an option (or after NAME= in one) that names a file of the package, made absolute.
std::string resolved(const std::string& token)
{
  const auto eq = token.find('=');
  const std::string head = eq == std::string::npos ? "" : token.substr(0, eq + 1);
  const std::string value = eq == std::string::npos ? token : token.substr(eq + 1);
  const fs::path candidate = docsRoot() / value;
  if (!value.empty() && value[0] != '-' && fs::path(value).is_relative() && fs::exists(candidate))
    return head + candidate.string();
  return token;
}

/// Runs one example; the failure message names the page and line.
void runExample(const Example& ex)
{
  SCOPED_TRACE(ex.where);
  ASSERT_TRUE(ex.has_block) << ex.where << ": the example marker is not followed by a ```yaml block";
  TempDir dir;
  std::vector<std::string> args;
  if (ex.kind == "costmap_tool")
  {
    args = {"--params", dir.write("example.yaml", ex.yaml)};
    for (const auto& option : ex.options)
      args.push_back(resolved(option));
  }
  else if (ex.kind == "zone_file")
  {
    ASSERT_TRUE(ex.options.empty()) << ex.where << ": a zone_file example takes no options";
    const std::string params = dir.write("params.yaml",
                                         "plugins:\n"
                                         "  - {name: zones, type: costmap_layers/KeepoutFilter}\n");
    args = {"--params", params, "--mask", "zones=" + dir.write("zones.yaml", ex.yaml)};
  }
  else
  {
    FAIL() << ex.where << ": unknown example kind '" << ex.kind << "' (costmap_tool, zone_file or none)";
  }
  if (std::find(args.begin(), args.end(), "--map") == args.end())
  {
    args.push_back("--map");
    args.push_back((docsRoot() / "test/data/maps/turtlebot3_world.yaml").string());
  }
  const ToolResult r = runTool(args, dir);
  EXPECT_EQ(r.exit_code, 0) << ex.where << ": costmap_tool failed:\n" << r.err;
  // A key no layer reads, a namespace no plugin has, a value overridden by another: documentation
  // errors even though the tool runs. (Other warnings describe the example's situation, e.g. the robot
  // in a keepout zone on the escape-mode example.)
  std::istringstream err(r.err);
  for (std::string line; std::getline(err, line);)
  {
    bool doc_error = false;
    for (const char* phrase : {"is not a parameter", "names no plugin", "not used", "is not one of", "ignored"})
      doc_error |= line.find(phrase) != std::string::npos;
    EXPECT_FALSE(doc_error) << ex.where << ": costmap_tool warned:\n" << line;
  }
  const nlohmann::json j = nlohmann::json::parse(r.lastLine(), nullptr, false);
  EXPECT_TRUE(j.is_object() && j.contains("width")) << ex.where << ": no JSON result line:\n" << r.out;
}

/// One `roslaunch costmap_layers FILE ARGS` found on a page.
struct LaunchLine
{
  std::string where;
  std::string file;
  std::vector<std::pair<std::string, std::string>> args;
};

/// Every `roslaunch costmap_layers FILE [name:=value ...]` of the pages, in code blocks and inline code,
/// shell continuations joined; the arguments end at the first word that is not name:=value. A FILE
/// with <...> (a placeholder) is not a line to run.
std::vector<LaunchLine> launchLines()
{
  static const std::regex line_re(R"(roslaunch\s+(?:-\S+\s+)*costmap_layers\s+([^\s`]+)([^`\n]*))");
  static const std::regex arg_re(R"(^([A-Za-z_][A-Za-z0-9_]*):=(\S+)$)");
  const fs::path root = docsRoot();
  std::vector<LaunchLine> result;
  for (const auto& page : pages(root))
  {
    const auto raw = linesOf(page);
    for (size_t i = 0; i < raw.size(); ++i)
    {
      std::string line = raw[i];
      const size_t start = i;
      while (!line.empty() && line.back() == '\\' && i + 1 < raw.size())
        line = line.substr(0, line.size() - 1) + " " + raw[++i];
      for (std::sregex_iterator it(line.begin(), line.end(), line_re), end; it != end; ++it)
      {
        LaunchLine l;
        l.where = fs::relative(page, root).string() + ":" + std::to_string(start + 1);
        l.file = (*it)[1];
        if (l.file.find('<') != std::string::npos) continue;
        std::istringstream words((*it)[2].str());
        for (std::string word; words >> word;)
        {
          std::smatch m;
          if (!std::regex_match(word, m, arg_re)) break;
          l.args.emplace_back(m[1], m[2]);
        }
        result.push_back(l);
      }
    }
  }
  return result;
}

/// $PWD, $HOME and a leading ~ in a launch argument, as the user's shell would expand them, with both
/// folders being `dir`.
std::string expandShell(std::string value, const fs::path& dir)
{
  for (const std::string var : {"$PWD", "${PWD}", "$HOME", "${HOME}"})
    for (size_t at; (at = value.find(var)) != std::string::npos;)
      value.replace(at, var.size(), dir.string());
  if (value.rfind("~/", 0) == 0) value = (dir / value.substr(2)).string();
  return value;
}
}  // namespace

TEST(DocExamples, EveryYamlBlockIsMarked)
{
  int runnable = 0, not_runnable = 0;
  for (const auto& ex : allExamples())
  {
    if (!ex.kind.empty() && !ex.has_block)
      ADD_FAILURE() << ex.where << ": the marker <!-- example: " << ex.kind
                    << " --> is not followed by a ```yaml block";
    if (ex.kind == "costmap_tool" || ex.kind == "zone_file")
      ++runnable;
    else if (ex.kind == "none")
    {
      ++not_runnable;
      // A reason of a few words at least: "none" alone says nothing to the next reader.
      EXPECT_GE(ex.reason.size(), 15u) << ex.where << ": <!-- example: none REASON --> needs a reason";
    }
    else if (ex.kind.empty())
      ADD_FAILURE() << ex.where << ": a ```yaml block without a marker: add <!-- example: costmap_tool ... --> "
                    << "before it, or <!-- example: none REASON --> when it cannot run on its own";
  }
  // The pages hold a few dozen blocks: a parser that found none must not pass.
  EXPECT_GE(runnable, 12);
  EXPECT_GE(runnable + not_runnable, 20);
}

TEST(DocExamples, EveryMarkedExampleRunsThroughCostmapTool)
{
  const auto examples = allExamples();
  int run = 0;
  for (const auto& ex : examples)
  {
    if (ex.kind.empty() || ex.kind == "none") continue;
    runExample(ex);
    ++run;
  }
  // One per plugin page at least, plus the zone file and the README's.
  EXPECT_GE(run, 12);
}

TEST(DocExamples, EveryPluginPageRunsAnExampleOfItsPlugin)
{
  const fs::path root = docsRoot();
  const std::string plugins_xml = readFile((root / "gradient_plugins.xml").string());
  static const std::regex class_name("<class\\s+name=\"costmap_layers/([A-Za-z0-9_]+)\"");
  int classes = 0;
  for (std::sregex_iterator it(plugins_xml.begin(), plugins_xml.end(), class_name), end; it != end; ++it)
  {
    ++classes;
    const std::string name = (*it)[1];
    const fs::path page = root / "docs" / "plugins" / (name + ".md");
    ASSERT_TRUE(fs::exists(page)) << "costmap_layers/" << name << " has no page " << page;
    bool loads_it = false;
    for (const auto& ex : examplesOf(page, root))
      loads_it |= ex.kind == "costmap_tool" && ex.yaml.find("costmap_layers/" + name) != std::string::npos;
    EXPECT_TRUE(loads_it) << page << " has no marked costmap_tool example that loads costmap_layers/" << name;
  }
  EXPECT_GE(classes, 11);
}

// Each launch line of the pages, dry-run: roslaunch --nodes parses the file with the line's arguments,
// evaluates every $(arg), $(find) and if/unless and loads every rosparam file, then lists the nodes it
// would start, without starting one or a master (it exits 1 on any error; --dump-params exits 0 even
// then). A file the line names as the user's own ($PWD/my_costmap.yaml, ~/maps/floor.yaml, a relative
// name) is given as an empty YAML map in a temporary folder that is both the working folder and $HOME; a
// value that names a file of the package (example/..., params/...) is that file, and must exist. Undeclared arguments,
// which roslaunch ignores, are check_links.py's.
TEST(DocExamples, EveryLaunchLineParsesInADryRun)
{
  const auto lines = launchLines();
  EXPECT_GE(lines.size(), 8u) << "the pages hold about ten launch lines: a parser that found none must not pass";
  for (const auto& l : lines)
  {
    SCOPED_TRACE(l.where);
    TempDir dir;
    // The file by its path in the source tree: by package and name, roslaunch refuses a name found twice
    // in the package's folder, which holds colcon's install/ copy when the build is inside the clone.
    const fs::path launch_file = docsRoot() / "launch" / l.file;
    ASSERT_TRUE(fs::exists(launch_file)) << l.where << ": no launch/" << l.file << " in the package";
    std::string cmd = "cd " + shellQuote(dir.path.string()) + " && HOME=" + shellQuote(dir.path.string()) +
                      " roslaunch --nodes " + shellQuote(launch_file.string());
    for (const auto& [name, raw] : l.args)
    {
      std::string value = expandShell(raw, dir.path);
      // A path into the package (example/warehouse.yaml) is the package's file, never a stand-in.
      static const std::regex package_path(R"(^(example|params|launch|test|docs|scripts)/.*)");
      if (std::regex_match(value, package_path)) value = (docsRoot() / value).string();
      const fs::path as_path = fs::path(value).is_absolute() ? fs::path(value) : dir.path / value;
      const bool users_file = value.find('/') != std::string::npos || fs::path(value).has_extension();
      const bool in_dir = as_path.lexically_normal().string().rfind(dir.path.string(), 0) == 0;
      if (users_file && in_dir && fs::path(value).extension() == ".yaml" && !fs::exists(as_path))
      {
        fs::create_directories(as_path.parent_path());
        std::ofstream(as_path) << "{}\n";
      }
      cmd += " " + shellQuote(name + ":=" + value);
    }
    cmd += " >" + shellQuote(dir.file("out.txt")) + " 2>&1";
    const int status = std::system(cmd.c_str());
    const std::string out = readFile(dir.file("out.txt"));
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << l.where << ": roslaunch --nodes " << launch_file.string() << " failed:\n"
        << out;
    // --nodes prints one /node_name a line; a launch file that starts nothing is not what a page shows.
    EXPECT_NE(out.find("/"), std::string::npos) << l.where << ": no node listed:\n" << out;
  }
}

TEST(DocExamples, LinksLaunchLinesAndProgramsResolve)
{
  const fs::path root = docsRoot();
  const std::string cmd = "python3 " +
                          shellQuote((fs::path(COSTMAP_LAYERS_SOURCE_DIR) / "test/docs/check_links.py").string()) +
                          " " + shellQuote(root.string());
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << cmd;
  EXPECT_EQ(WEXITSTATUS(status), 0) << cmd << " found problems (listed above)";
}
