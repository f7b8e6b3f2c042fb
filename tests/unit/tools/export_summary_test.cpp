// Every exporter ends with one line that says what it wrote, where the generated files went,
// the losses by kind and the option that accepts them (issue 40: "Outputs that say what they
// did"). The counts are checked against the findings printed above the line and the files on
// disk, not against the code that writes the line.
#include <doctest/doctest.h>

#include "support/export_helpers.h"
#include "support/run_command.h"

#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using bodyfmt::test::fresh_dir;
using bodyfmt::test::run_command;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Losses by kind, counted from the `[export-loss]` findings printed.
std::map<std::string, int> printed_losses(const std::vector<std::string>& lines) {
  static const std::regex kind(R"(\(loss kind: ([a-z-]+)\) \[export-loss\]$)");
  std::map<std::string, int> counts;
  std::smatch m;
  for (const std::string& line : lines)
    if (std::regex_search(line, m, kind)) counts[m[1]] += 1;
  return counts;
}

int regular_files_in(const fs::path& folder) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(folder))
    n += entry.is_regular_file() && entry.path().filename() != ".bodyfmt-export" ? 1 : 0;
  return n;
}

std::string examples(const std::string& name) { return std::string(BODYFMT_EXAMPLES_DIR) + "/" + name; }

}  // namespace

TEST_CASE("body2urdf ends with one line: the URDF, its mesh folder, losses by kind and --allow-loss") {
  const fs::path dir = fresh_dir("export_summary_urdf");
  const auto r = run_command(std::string(BODYFMT_BODY2URDF) + " " + examples("simpletank.body") + " -o out/tank.urdf",
                             dir.string());
  REQUIRE(r.status == 1);
  const std::vector<std::string> lines = lines_of(r.output);
  REQUIRE(!lines.empty());
  const std::map<std::string, int> losses = printed_losses(lines);
  REQUIRE(!losses.empty());
  int total = 0;
  for (const auto& [kind, count] : losses) total += count;
  const std::string& last = lines.back();
  INFO(last);
  CHECK(last.rfind("body2urdf: wrote out/tank.urdf and ", 0) == 0);
  const int meshes = regular_files_in(dir / "out/meshes/tank");
  CHECK(last.find(std::to_string(meshes) + " files in out/meshes/tank/") != std::string::npos);
  CHECK(last.find("; " + std::to_string(total) + " losses (") != std::string::npos);
  std::string kinds;
  for (const auto& [kind, count] : losses) {
    CHECK(last.find(std::to_string(count) + " " + kind) != std::string::npos);
    CHECK(last.find("--allow-loss ") != std::string::npos);
    CHECK(last.find(kind, last.find("--allow-loss ")) != std::string::npos);
    kinds += (kinds.empty() ? "" : ",") + kind;
  }
  CHECK(last.size() <= 200);

  // Accepting every kind the line names exits 0 and offers no option again.
  const auto accepted = run_command(
      std::string(BODYFMT_BODY2URDF) + " " + examples("simpletank.body") + " -o out/tank.urdf --allow-loss " + kinds,
      dir.string());
  CHECK(accepted.status == 0);
  const std::string again = lines_of(accepted.output).back();
  CHECK(again.rfind("body2urdf: wrote out/tank.urdf", 0) == 0);
  CHECK(again.find("--allow-loss") == std::string::npos);
}

TEST_CASE("body2mjcf, body2gltf and urdf2body end with the line of what they wrote") {
  const fs::path dir = fresh_dir("export_summary_others");
  const auto mjcf =
      run_command(std::string(BODYFMT_BODY2MJCF) + " " + examples("arm.body") + " -o arm.xml", dir.string());
  REQUIRE(mjcf.status != 2);
  const std::string mjcf_last = lines_of(mjcf.output).back();
  INFO(mjcf_last);
  CHECK(mjcf_last.rfind("body2mjcf: wrote arm.xml", 0) == 0);
  CHECK((printed_losses(lines_of(mjcf.output)).empty() == (mjcf_last.find("nothing lost") != std::string::npos)));

  const auto glb =
      run_command(std::string(BODYFMT_BODY2GLTF) + " " + examples("arm.body") + " -o arm.glb", dir.string());
  REQUIRE(glb.status != 2);
  const std::string glb_last = lines_of(glb.output).back();
  INFO(glb_last);
  CHECK(glb_last.rfind("body2gltf: wrote arm.glb", 0) == 0);

  REQUIRE(
      run_command(std::string(BODYFMT_BODY2URDF) + " " + examples("arm.body") + " -o arm.urdf", dir.string()).status !=
      2);
  const auto back = run_command(std::string(BODYFMT_URDF2BODY) + " arm.urdf -o back.body", dir.string());
  REQUIRE(back.status != 2);
  const std::string back_last = lines_of(back.output).back();
  INFO(back_last);
  CHECK(back_last.rfind("urdf2body: wrote back.body", 0) == 0);
}

TEST_CASE("an export that is not written ends with why, never with the line of what was written") {
  const fs::path dir = fresh_dir("export_summary_refused");
  const auto r = run_command(
      std::string(BODYFMT_BODY2URDF) + " " + examples("simpletank.body") + " -o tank.urdf --strict", dir.string());
  CHECK(r.status == 2);
  const std::string last = lines_of(r.output).back();
  CHECK(last.find("wrote") == std::string::npos);
  CHECK(last.find("tank.urdf was not written") != std::string::npos);
}
