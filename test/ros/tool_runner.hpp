// Runs the built costmap_tool as a user would (a child process) and collects what it printed.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace costmap_layers_test
{
struct ToolResult
{
  int exit_code = -1;
  std::string out;
  std::string err;
  /// The last non-empty line of stdout.
  std::string lastLine() const
  {
    std::istringstream in(out);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    return last;
  }
};

inline std::string shellQuote(const std::string& s)
{
  std::string q = "'";
  for (char c : s)
    q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A fresh temporary folder, removed with the object.
struct TempDir
{
  std::filesystem::path path;
  TempDir()
  {
    std::string tmpl = (std::filesystem::temp_directory_path() / "costmap_tool_test_XXXXXX").string();
    path = mkdtemp(tmpl.data());
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::string write(const std::string& name, const std::string& text) const
  {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
};

inline ToolResult runTool(const std::vector<std::string>& args, const TempDir& dir)
{
  std::string cmd = shellQuote(COSTMAP_TOOL_PATH);
  for (const auto& a : args)
    cmd += " " + shellQuote(a);
  const std::string out_file = dir.file("stdout.txt"), err_file = dir.file("stderr.txt");
  cmd += " >" + shellQuote(out_file) + " 2>" + shellQuote(err_file);
  const int status = std::system(cmd.c_str());
  ToolResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  r.out = readFile(out_file);
  r.err = readFile(err_file);
  return r;
}

/// Writes a binary PGM (row 0 of the image = top = highest y) and its map_server YAML.
inline std::string writeMap(const TempDir& dir, const std::string& name, int w, int h,
                            const std::vector<uint8_t>& pixels, double resolution, double ox, double oy,
                            const std::string& mode = "trinary")
{
  std::ofstream pgm(dir.file(name + ".pgm"), std::ios::binary);
  pgm << "P5\n" << w << " " << h << "\n255\n";
  pgm.write(reinterpret_cast<const char*>(pixels.data()), static_cast<std::streamsize>(pixels.size()));
  pgm.close();
  std::ostringstream yaml;
  yaml << "image: " << name << ".pgm\nresolution: " << resolution << "\norigin: [" << ox << ", " << oy
       << ", 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: " << mode << "\n";
  return dir.write(name + ".yaml", yaml.str());
}
}  // namespace costmap_layers_test
