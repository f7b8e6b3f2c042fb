// Where the exporters write, from the user's side: they never write over an input of the run,
// write through symbolic links, write pipes, devices and standard output in place, and keep the
// generated meshes of different exports apart (issue 15, "Outputs never destroy what they
// should not").
#include <doctest/doctest.h>

#include "support/export_helpers.h"
#include "support/run_command.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using bodyfmt::test::fresh_dir;
using bodyfmt::test::read;
using bodyfmt::test::run_command;

struct Exporter {
  std::string name;
  std::string binary;
  std::string extension;
  std::string mesh_base;  ///< the default folder of generated meshes, before the output's stem
};

const std::vector<Exporter>& exporters() {
  static const std::vector<Exporter> all = {{"body2urdf", BODYFMT_BODY2URDF, ".urdf", "meshes"},
                                            {"body2mjcf", BODYFMT_BODY2MJCF, ".xml", "assets"},
                                            {"body2gltf", BODYFMT_BODY2GLTF, ".glb", ""}};
  return all;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

/// One link with a Cone (a generated mesh in URDF and MJCF) of the given height.
std::string cone_model(const std::string& name, const std::string& height, const std::string& extra = "",
                       const std::string& link = "ARM") {
  return "format: ChoreonoidBody\nformat_version: 2.0\nname: " + name +
         "\nlinks:\n"
         "  - name: " +
         link +
         "\n"
         "    joint_type: free\n"
         "    mass: 1\n"
         "    inertia: [ 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01 ]\n"
         "    elements:\n"
         "      - { type: Shape, geometry: { type: Cone, radius: 0.05, height: " +
         height + " } }\n" + extra;
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("outputs: no exporter writes over an input of its run: the model, a SubBody, a mesh, a link to one") {
  const fs::path dir = fresh_dir("inputs");
  const std::string stl =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\nendfacet\n"
      "endsolid t\n";
  write(dir / "parts" / "plate.stl", stl);
  const std::string sub = cone_model("Sub", "0.1", "", "TIP");
  write(dir / "sub.body", sub);
  const std::string model =
      cone_model("Main", "0.2",
                 "      - { type: Shape, geometry: { type: Resource, uri: parts/plate.stl } }\n"
                 "  - { name: TOOL, type: SubBody, uri: sub.body, parent: ARM, translation: [0, 0, 0.3] }\n");
  write(dir / "main.body", model);
  for (const Exporter& tool : exporters()) {
    CAPTURE(tool.name);
    // Links named as the tool's output (body2gltf wants .glb) reach every kind of input.
    for (const char* link : {"model", "sub", "plate"}) fs::remove(dir / (link + tool.extension));
    fs::create_symlink("main.body", dir / ("model" + tool.extension));
    fs::create_symlink("sub.body", dir / ("sub" + tool.extension));
    fs::create_symlink("parts/plate.stl", dir / ("plate" + tool.extension));
    std::vector<std::pair<std::string, std::string>> targets = {
        {"model" + tool.extension, "it is the model of this run ('"},
        {"sub" + tool.extension, "it is a model file it includes of this run ('"},
        {"plate" + tool.extension, "it is a mesh of the model of this run ('"}};
    if (tool.extension != ".glb") {
      targets.emplace_back("main.body", "it is the model of this run ('");
      targets.emplace_back("sub.body", "it is a model file it includes of this run ('");
      targets.emplace_back("parts/plate.stl", "it is a mesh of the model of this run ('");
    }
    for (const auto& entry : targets) {
      const std::string& target = entry.first;  // not a structured binding: CAPTURE's lambda takes it
      const std::string& why = entry.second;
      CAPTURE(target);
      const auto r = run_command("'" + tool.binary + "' -q main.body -o " + target, dir.string());
      CHECK(r.status == 2);
      CHECK(contains(r.output, "cannot write '" + target + "': " + why));
      CHECK(contains(r.output, target + " was not written"));
    }
    CHECK(read(dir / "main.body") == model);
    CHECK(read(dir / "sub.body") == sub);
    CHECK(read(dir / "parts" / "plate.stl") == stl);
    CHECK(fs::is_symlink(dir / ("model" + tool.extension)));
  }
  fs::remove_all(dir);
}

TEST_CASE("outputs: a symbolic link is written through, a FIFO and /dev/null in place, '-' to standard output") {
  const fs::path dir = fresh_dir("special");
  write(dir / "m.body", cone_model("M", "0.2"));
  for (const Exporter& tool : exporters()) {
    CAPTURE(tool.name);
    const std::string exe = "'" + tool.binary + "' -q m.body";
    // A link into another folder: the link stays, its target gets the export.
    fs::remove_all(dir / "real");
    fs::create_directories(dir / "real");
    fs::remove(dir / ("link" + tool.extension));
    fs::create_symlink("real/target" + tool.extension, dir / ("link" + tool.extension));
    CHECK(run_command(exe + " -o link" + tool.extension, dir.string()).status == 0);
    CHECK(fs::is_symlink(dir / ("link" + tool.extension)));
    const std::string through = read(dir / "real" / ("target" + tool.extension));
    CHECK(through.size() > 100);
    // A named pipe: read by `cat` while the tool writes it; it stays a pipe.
    fs::remove(dir / "pipe");
    REQUIRE(::mkfifo((dir / "pipe").c_str(), 0600) == 0);
    const auto piped = run_command(
        "timeout 20 cat pipe > from_pipe & timeout 20 " + exe + " -o pipe; status=$?; wait; echo status=$status",
        dir.string());
    INFO(piped.output);
    CHECK(contains(piped.output, "status=0"));
    CHECK(fs::is_fifo(dir / "pipe"));
    REQUIRE(run_command(exe + " -o pipe" + tool.extension, dir.string()).status == 0);  // same stem
    CHECK(read(dir / "from_pipe") == read(dir / ("pipe" + tool.extension)));
    // /dev/null stays the device (CI runs as root, where a rename over it would succeed).
    CHECK(run_command(exe + " -o /dev/null", dir.string()).status == 0);
    CHECK(fs::is_character_file("/dev/null"));
    // '-': the main file on standard output, byte for byte what a file gets; generated files
    // go under the current folder, named after the model (M) as a file M.urdf would name them.
    const auto out = run_command(exe + " -o - 2>/dev/null", dir.string(), false);
    CHECK(out.status == 0);
    REQUIRE(run_command(exe + " -o M" + tool.extension, dir.string()).status == 0);
    CHECK(out.output == read(dir / ("M" + tool.extension)));
  }
  fs::remove_all(dir);
}

TEST_CASE("outputs: two exports into one folder keep their own generated meshes") {
  const fs::path dir = fresh_dir("two");
  write(dir / "a.body", cone_model("A", "0.2"));
  write(dir / "b.body", cone_model("B", "0.4"));
  for (const Exporter& tool : exporters()) {
    if (tool.mesh_base.empty()) continue;  // GLB embeds its meshes
    CAPTURE(tool.name);
    for (const char* name : {"a", "b"}) {
      const auto r =
          run_command("'" + tool.binary + "' -q " + name + ".body -o out/" + name + tool.extension, dir.string());
      CHECK(r.status == 0);
    }
    // Each export's meshes live under a folder named after its output's stem.
    const fs::path a_mesh = dir / "out" / tool.mesh_base / "a" / "ARM_shape0.stl";
    const fs::path b_mesh = dir / "out" / tool.mesh_base / "b" / "ARM_shape0.stl";
    REQUIRE(fs::exists(a_mesh));
    REQUIRE(fs::exists(b_mesh));
    CHECK(read(a_mesh) != read(b_mesh));  // a 0.2 m and a 0.4 m cone
    const std::string a_text = read(dir / "out" / ("a" + tool.extension));
    CHECK((contains(a_text, tool.mesh_base + "/a/ARM_shape0.stl") ||
           (contains(a_text, "meshdir=\"" + tool.mesh_base + "/a\"") && contains(a_text, "\"ARM_shape0.stl\""))));
    CHECK(!contains(a_text, "/b/"));
  }
  fs::remove_all(dir);
}

TEST_CASE("outputs: a file another export wrote, or the user's own, is never replaced in a shared mesh folder") {
  const fs::path dir = fresh_dir("shared");
  write(dir / "a.body", cone_model("A", "0.2"));
  write(dir / "b.body", cone_model("B", "0.4"));
  for (const Exporter& tool : exporters()) {
    if (tool.mesh_base.empty()) continue;
    CAPTURE(tool.name);
    fs::remove_all(dir / "out");
    const std::string a = "'" + tool.binary + "' -q a.body -o out/a" + tool.extension + " --mesh-folder shared";
    const std::string b = "'" + tool.binary + "' -q b.body -o out/b" + tool.extension + " --mesh-folder shared";
    REQUIRE(run_command(a, dir.string()).status == 0);
    const std::string a_bytes = read(dir / "out" / "shared" / "ARM_shape0.stl");
    const auto clash = run_command(b, dir.string());
    CHECK(clash.status == 2);
    CHECK(contains(clash.output,
                   "cannot write 'out/shared/ARM_shape0.stl': it was written by the export to "
                   "'out/a" +
                       tool.extension + "'"));
    CHECK(read(dir / "out" / "shared" / "ARM_shape0.stl") == a_bytes);
    CHECK(!fs::exists(dir / "out" / ("b" + tool.extension)));
    // The export that wrote the file may replace it when its model changes.
    write(dir / "a.body", cone_model("A", "0.3"));
    CHECK(run_command(a, dir.string()).status == 0);
    CHECK(read(dir / "out" / "shared" / "ARM_shape0.stl") != a_bytes);
    write(dir / "a.body", cone_model("A", "0.2"));
    // A file no export wrote is the user's: kept, and nothing is written.
    write(dir / "out" / "mine" / "ARM_shape0.stl", "my own mesh");
    const auto own =
        run_command("'" + tool.binary + "' -q a.body -o out/c" + tool.extension + " --mesh-folder mine", dir.string());
    CHECK(own.status == 2);
    CHECK(contains(own.output, "a file of that name exists that this export did not write"));
    CHECK(read(dir / "out" / "mine" / "ARM_shape0.stl") == "my own mesh");
    CHECK(!fs::exists(dir / "out" / ("c" + tool.extension)));
  }
  fs::remove_all(dir);
}

TEST_CASE("outputs: bodycheck -o never writes its report over a model it checks, a file it includes or a link") {
  const fs::path dir = fresh_dir("report");
  const std::string sub = cone_model("Sub", "0.1", "", "TIP");
  write(dir / "sub.body", sub);
  const std::string model = cone_model(
      "Main", "0.2", "  - { name: TOOL, type: SubBody, uri: sub.body, parent: ARM, translation: [0, 0, 0.3] }\n");
  write(dir / "main.body", model);
  fs::create_symlink("main.body", dir / "link.txt");
  fs::create_hard_link(dir / "sub.body", dir / "hard.txt");
  const std::string exe = "'" + std::string(BODYFMT_BODYCHECK) + "' ";
  for (const auto& entry :
       std::vector<std::pair<std::string, std::string>>{{"main.body", "it is the model of this run ('main.body')"},
                                                        {"link.txt", "it is the model of this run ('main.body')"},
                                                        {"sub.body", "it is a model file it includes of this run ('"},
                                                        {"hard.txt", "it is a model file it includes of this run ('"},
                                                        {".", "it is a folder"}}) {
    const std::string& target = entry.first;  // not a structured binding: CAPTURE's lambda takes it
    const std::string& why = entry.second;
    CAPTURE(target);
    for (const char* format : {"text", "json", "sarif"}) {
      const auto r = run_command(exe + "main.body --format " + format + " -o " + target, dir.string());
      CHECK(r.status == 2);
      CHECK(contains(r.output, target + ": cannot write the report: " + why));
    }
  }
  // Named twice, through a folder: still the model.
  const auto folder = run_command(exe + ". -o main.body", dir.string());
  CHECK(folder.status == 2);
  CHECK(contains(folder.output, "main.body: cannot write the report: it is the model of this run"));
  CHECK(read(dir / "main.body") == model);
  CHECK(read(dir / "sub.body") == sub);
  CHECK(fs::is_symlink(dir / "link.txt"));
  // Any other file, and a link to one, is written (through the link).
  write(dir / "elsewhere" / "old.txt", "old");
  fs::create_symlink("elsewhere/old.txt", dir / "report.txt");
  CHECK(run_command(exe + "-q main.body --format json -o report.txt", dir.string()).status == 0);
  CHECK(contains(read(dir / "elsewhere" / "old.txt"), "\"diagnostics\""));
  fs::remove_all(dir);
}

TEST_CASE("outputs: a symbolic link planted where an exporter chooses the names is refused, never followed") {
  const fs::path dir = fresh_dir("planted");
  write(dir / "m.body", cone_model("M", "0.2"));
  write(dir / "victim.txt", "precious");
  fs::create_directories(dir / "elsewhere");
  for (const Exporter& tool : exporters()) {
    if (tool.mesh_base.empty()) continue;
    CAPTURE(tool.name);
    const std::string exe = "'" + tool.binary + "' -q m.body -o out/g" + tool.extension;
    // The export's own mesh folder, a link to another folder.
    fs::remove_all(dir / "out");
    fs::create_directories(dir / "out" / tool.mesh_base);
    fs::create_symlink(fs::absolute(dir / "elsewhere"), dir / "out" / tool.mesh_base / "g");
    auto r = run_command(exe, dir.string());
    CHECK(r.status == 2);
    CHECK(contains(r.output, "cannot write 'out/" + tool.mesh_base + "/g': it is a symbolic link"));
    CHECK(fs::is_empty(dir / "elsewhere"));
    CHECK(!fs::exists(dir / "out" / ("g" + tool.extension)));
    // The base folder a link: the same.
    fs::remove_all(dir / "out");
    fs::create_directories(dir / "out");
    fs::create_symlink(fs::absolute(dir / "elsewhere"), dir / "out" / tool.mesh_base);
    r = run_command(exe, dir.string());
    CHECK(r.status == 2);
    CHECK(contains(r.output, "cannot write 'out/" + tool.mesh_base + "': it is a symbolic link"));
    CHECK(fs::is_empty(dir / "elsewhere"));
    // A mesh the export wrote, replaced by a link to any file; then its record.
    fs::remove_all(dir / "out");
    REQUIRE(run_command(exe, dir.string()).status == 0);
    const fs::path mesh = dir / "out" / tool.mesh_base / "g" / "ARM_shape0.stl";
    REQUIRE(fs::is_regular_file(mesh));
    write(dir / "m.body", cone_model("M", "0.3"));  // new bytes for the mesh
    fs::remove(mesh);
    fs::create_symlink(fs::absolute(dir / "victim.txt"), mesh);
    r = run_command(exe, dir.string());
    CHECK(r.status == 2);
    CHECK(contains(r.output, "cannot write 'out/" + tool.mesh_base + "/g/ARM_shape0.stl': it is a symbolic link"));
    CHECK(read(dir / "victim.txt") == "precious");
    fs::remove(mesh);
    const fs::path record = dir / "out" / tool.mesh_base / "g" / ".bodyfmt-export";
    fs::remove(record);
    fs::create_symlink(fs::absolute(dir / "victim.txt"), record);
    r = run_command(exe, dir.string());
    CHECK(r.status == 2);
    CHECK(contains(r.output, "/g/.bodyfmt-export': it is a symbolic link"));
    CHECK(read(dir / "victim.txt") == "precious");
    // A FIFO where a mesh goes would block: refused too.
    fs::remove(record);
    REQUIRE(::mkfifo(mesh.c_str(), 0600) == 0);
    r = run_command("timeout 20 " + exe, dir.string());
    CHECK(r.status == 2);
    CHECK(contains(r.output, "/g/ARM_shape0.stl': it is not a regular file"));
    write(dir / "m.body", cone_model("M", "0.2"));
  }
  // glTF: the .bin beside a .gltf and the textures folder.
  const fs::path data = fs::path(BODYFMT_TEST_DATA_DIR) / "gltf";
  for (const char* file : {"textured.body", "quad.obj", "checker.png"}) fs::copy_file(data / file, dir / file);
  const std::string gltf = "'" + std::string(BODYFMT_BODY2GLTF) + "' -q textured.body -o out/t.gltf";
  fs::remove_all(dir / "out");
  REQUIRE(run_command(gltf, dir.string()).status == 0);
  REQUIRE(fs::is_regular_file(dir / "out" / "t.bin"));
  std::vector<fs::path> generated;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out" / "textures"))
    if (entry.is_regular_file() && entry.path().extension() == ".png") generated.push_back(entry.path());
  REQUIRE(!generated.empty());
  generated.push_back(dir / "out" / "t.bin");
  for (const fs::path& file : generated) {
    CAPTURE(file);
    fs::remove(file);
    fs::create_symlink(fs::absolute(dir / "victim.txt"), file);
    const auto r = run_command(gltf, dir.string());
    CHECK(r.status == 2);
    CHECK(contains(r.output, "': it is a symbolic link"));
    CHECK(read(dir / "victim.txt") == "precious");
    fs::remove(file);
  }
  fs::remove_all(dir / "out");
  fs::create_directories(dir / "out" / "textures");
  fs::create_symlink(fs::absolute(dir / "elsewhere"), dir / "out" / "textures" / "t");
  const auto folder = run_command(gltf, dir.string());
  CHECK(folder.status == 2);
  CHECK(contains(folder.output, "cannot write 'out/textures/t': it is a symbolic link"));
  CHECK(fs::is_empty(dir / "elsewhere"));
  fs::remove_all(dir);
}

TEST_CASE("outputs: a refused export creates nothing, not even an empty mesh folder") {
  const fs::path dir = fresh_dir("refused");
  write(dir / "m.body", cone_model("M", "0.2"));
  for (const Exporter& tool : exporters()) {
    CAPTURE(tool.name);
    const auto r = run_command("'" + tool.binary + "' -q m.body -o ''", dir.string());
    CHECK(r.status == 2);
    // body2gltf refuses it earlier, by its extension.
    CHECK(
        contains(r.output, tool.mesh_base.empty() ? "-o must name a .glb or .gltf file" : "the output path is empty"));
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
    CHECK(left == std::vector<std::string>{"m.body"});
  }
  fs::remove_all(dir);
}
