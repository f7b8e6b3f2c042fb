// converters/core and export: atomic output, names, numbers, mesh bytes.
#include <bodyfmt/converters/loss.h>
#include <bodyfmt/converters/mesh_writer.h>
#include <bodyfmt/converters/names.h>
#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/converters/staged_files.h>

#include <doctest/doctest.h>

#include "support/export_helpers.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace bodyfmt;
using namespace bodyfmt::converters;

namespace {

using bodyfmt::test::fresh_dir;
using bodyfmt::test::read;

int count_entries(const fs::path& dir) {
  int n = 0;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) ++n;
  return n;
}

}  // namespace

TEST_CASE("converters: OutputSet writes every staged file on commit and nothing before") {
  const fs::path dir = fresh_dir("commit");
  OutputSet out(dir / "robot.urdf");
  out.set_main("<robot/>");
  out.add("meshes/a.stl", "abc");
  CHECK(count_entries(dir) == 0);
  CollectingSink sink;
  REQUIRE(out.commit(sink));
  CHECK(read(dir / "robot.urdf") == "<robot/>");
  CHECK(read(dir / "meshes/a.stl") == "abc");
  CHECK(read(dir / "meshes" / OutputSet::kRecordName) == "a.stl\t../robot.urdf\n");
  // robot.urdf, meshes/, meshes/a.stl, the record: no temporary files left
  CHECK(count_entries(dir) == 4);
  fs::remove_all(dir);
}

TEST_CASE("converters: a FIFO in place of a folder's record is refused, never read") {
  // Opened, a FIFO with no writer blocks a reader for good: the record path is checked first, and
  // the record is read only through the bounded reader, which takes regular files only.
  const fs::path dir = fresh_dir("record_fifo");
  fs::create_directories(dir / "meshes");
  REQUIRE(::mkfifo((dir / "meshes" / OutputSet::kRecordName).c_str(), 0600) == 0);
  { std::ofstream(dir / "meshes/a.stl") << "not ours"; }
  OutputSet out(dir / "robot.urdf");
  out.set_main("<robot/>");
  out.add("meshes/a.stl", "abc");
  CollectingSink sink;
  CHECK_FALSE(out.commit(sink));  // a.stl is a file this export cannot show it wrote
  CHECK(read(dir / "meshes/a.stl") == "not ours");
  CHECK_FALSE(fs::exists(dir / "robot.urdf"));
  fs::remove_all(dir);
}

TEST_CASE("converters: a failed commit keeps the existing output and leaves no partial file") {
  const fs::path dir = fresh_dir("fail");
  { std::ofstream(dir / "robot.urdf") << "old"; }
  { std::ofstream(dir / "meshes") << "a file where the mesh folder should go"; }
  OutputSet out(dir / "robot.urdf");
  out.set_main("new");
  out.add("meshes/a.stl", "abc");
  CollectingSink sink;
  CHECK_FALSE(out.commit(sink));
  REQUIRE(sink.diagnostics().size() == 1);
  CHECK(sink.diagnostics()[0].rule_id == "export-write");
  CHECK(sink.diagnostics()[0].severity == Severity::kFatal);
  CHECK(read(dir / "robot.urdf") == "old");
  CHECK(count_entries(dir) == 2);  // no temporary file
  fs::remove_all(dir);
}

TEST_CASE("converters: after fail() commit writes nothing") {
  const fs::path dir = fresh_dir("failed");
  OutputSet out(dir / "robot.urdf");
  out.set_main("x");
  out.fail();
  CollectingSink sink;
  CHECK_FALSE(out.commit(sink));
  CHECK(sink.diagnostics().empty());
  CHECK(count_entries(dir) == 0);
  fs::remove_all(dir);
}

TEST_CASE("converters: report_loss emits export-loss at the given location") {
  CollectingSink sink;
  report_loss(sink, SourceLocation{"a.body", 12, 7}, "URDF", LossKind::kTextures, "a texture", "colours are kept");
  REQUIRE(sink.diagnostics().size() == 1);
  const Diagnostic& d = sink.diagnostics()[0];
  CHECK(d.rule_id == "export-loss");
  CHECK(d.severity == Severity::kWarning);
  CHECK(d.location.line == 12);
  CHECK(d.location.column == 7);
  CHECK(d.fix_hint == "colours are kept");
}

TEST_CASE("converters: numbers are shortest round-trip and never -0") {
  CHECK(format_number(0.1 + 0.2) == "0.30000000000000004");
  CHECK(format_number(1.0) == "1");
  CHECK(format_number(-0.0) == "0");
  CHECK(format_number(1e-5) == "1e-05");
  CHECK(std::stod(format_number(M_PI)) == M_PI);
  CHECK(format_vector(Eigen::Vector3d(1, -0.0, 2.5)) == "1 0 2.5");
}

TEST_CASE("converters: XML escaping, comments and URDF names") {
  CHECK(xml_escape("a<b>&\"c'") == "a&lt;b&gt;&amp;&quot;c&apos;");
  CHECK(xml_comment_text("a--b-") == "a- -b- ");
  CHECK(is_xml_text("caf\xc3\xa9"));
  CHECK_FALSE(is_xml_text("bad\x01"));
  CHECK_FALSE(is_xml_text("\xff"));
  CHECK_FALSE(is_xml_text("\xef\xbf\xbe"));            // U+FFFE, a non-character XML does not allow
  CHECK_FALSE(is_xml_text("\xef\xbf\xbf"));            // U+FFFF
  CHECK_FALSE(is_xml_text("\xed\xa0\x80"));            // a surrogate
  CHECK_FALSE(is_xml_text("\xc0\xaf"));                // overlong
  CHECK(is_xml_text("\xef\xbf\xbd\xf0\x9f\x98\x80"));  // U+FFFD, U+1F600
  CHECK(urdf_name_problem("RARM_WRIST_R").empty());
  CHECK(urdf_name_problem("link-1.a").empty());
  CHECK_FALSE(urdf_name_problem("").empty());
  CHECK_FALSE(urdf_name_problem("1link").empty());
  CHECK_FALSE(urdf_name_problem("upper arm").empty());
  CHECK(file_stem("a b/c") == "a_b_c");
  CHECK(file_stem(".hidden") == "_.hidden");
}

TEST_CASE("converters: binary STL layout and deterministic DAE") {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  const std::string stl = write_stl(mesh);
  CHECK(stl.size() == 80 + 4 + 50);
  CHECK(stl.rfind("solid", 0) != 0);
  float nz;
  std::memcpy(&nz, stl.data() + 84 + 8, 4);
  CHECK(nz == 1.0f);
  std::string error;
  Material m;
  m.diffuse_color = {1, 0, 0};
  const auto a = write_dae(mesh, m, "tri", error);
  REQUIRE(a);
  const auto b = write_dae(mesh, m, "tri", error);
  REQUIRE(b);
  CHECK(*a == *b);
  CHECK(a->find("<created>2000-01-01T00:00:00</created>") != std::string::npos);
}

TEST_CASE("converters: a commit that fails partway puts every earlier file back") {
  const fs::path dir = fresh_dir("partway");
  { std::ofstream(dir / "robot.urdf") << "old main"; }
  fs::create_directories(dir / "meshes" / "b.stl" / "occupied");  // a folder where b.stl should go
  { std::ofstream(dir / "meshes" / "a.stl") << "old a"; }
  OutputSet out(dir / "robot.urdf");
  out.set_main("new main");
  out.add("meshes/a.stl", "new a");  // renamed first, then b.stl fails
  out.add("meshes/b.stl", "new b");
  CollectingSink sink;
  CHECK_FALSE(out.commit(sink));
  REQUIRE(sink.diagnostics().size() == 1);
  CHECK(sink.diagnostics()[0].rule_id == "export-write");
  CHECK(read(dir / "robot.urdf") == "old main");
  CHECK(read(dir / "meshes" / "a.stl") == "old a");
  // robot.urdf, meshes/, a.stl, the folder b.stl and what is in it: no temporary or backup file.
  CHECK(count_entries(dir) == 5);
  for (const auto& entry : fs::recursive_directory_iterator(dir)) CHECK(entry.path().filename().string()[0] != '.');
  fs::remove_all(dir);
}

TEST_CASE("converters: a staged path that leaves the output folder is refused at commit") {
  const fs::path dir = fresh_dir("outside");
  for (const char* bad : {"../escape.stl", "meshes/../../escape.stl", "/tmp/escape.stl"}) {
    CAPTURE(bad);
    OutputSet out(dir / "robot.urdf");
    out.set_main("main");
    out.add(bad, "x");
    CollectingSink sink;
    CHECK_FALSE(out.commit(sink));
    CHECK(sink.has("export-write"));
    CHECK(count_entries(dir) == 0);
  }
  fs::remove_all(dir);
}

TEST_CASE("converters: copied meshes land inside the output folder whatever their source path") {
  const fs::path dir = fresh_dir("copies");
  const fs::path source = fresh_dir("copies_source") / "deep" / "..";
  fs::create_directories(source / "deep");
  { std::ofstream(source / "part.stl") << "solid x\nendsolid x\n"; }
  OutputSet out(dir / "robot.urdf");
  StagedFiles staged(out, "meshes");
  std::string error;
  const auto relative = staged.copy((source / "deep" / ".." / "part.stl").string(), error);
  REQUIRE(relative);
  CHECK(*relative == "meshes/part.stl");
  const auto again = staged.copy((source / "part.stl").string(), error);
  REQUIRE(again);
  CHECK(*again == "meshes/part.stl");  // the same file spelled another way: copied once
  CHECK(out.files().size() == 1);
  fs::remove_all(dir);
}
