#include "support/export_helpers.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace bodyfmt::test {

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("bodyfmt_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::vector<int> marked_lines(const std::filesystem::path& file, const std::string& marker) {
  std::vector<int> lines;
  std::istringstream in(read(file));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.find(marker) != std::string::npos && line.find('#') != 0) lines.push_back(n);
  return lines;
}

std::vector<int> reported_lines(const std::vector<Diagnostic>& diagnostics, const std::string& rule) {
  std::vector<int> lines;
  for (const Diagnostic& d : diagnostics)
    if (d.rule_id == rule) lines.push_back(d.location.line);
  std::sort(lines.begin(), lines.end());
  return lines;
}

}  // namespace bodyfmt::test
