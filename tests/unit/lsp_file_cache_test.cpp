// LoadOptions::file_cache (bodyfmt/file_cache.h), which bodyls keeps across keystrokes: a load
// with it reads no unchanged mesh or included file again, and finds what a load without it finds.
#include "support/export_helpers.h"

#include <bodyfmt/file_cache.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::vector<std::string> findings(const std::string& text, const fs::path& file,
                                  std::shared_ptr<bodyfmt::FileCache> cache) {
  bodyfmt::LoadOptions options;
  options.file_cache = std::move(cache);
  bodyfmt::CollectingSink sink;
  REQUIRE(bodyfmt::load_body_string(text, file.string(), options, sink));
  std::vector<std::string> out;
  for (const bodyfmt::Diagnostic& d : sink.diagnostics()) out.push_back(bodyfmt::format_diagnostic(d));
  return out;
}

const char* const kSub =
    "format: ChoreonoidBody\nformat_version: 2.0\nname: S\nroot_link: S0\nlinks:\n"
    "  - { name: S0, joint_type: fixed, mass: -1, inertia: [1,0,0,0,1,0,0,0,1] }\n";

std::string model(const std::string& padding) {
  return "format: ChoreonoidBody\nformat_version: 2.0\nname: M\nroot_link: BASE\nlinks:\n" + padding +
         "  - name: BASE\n    joint_type: free\n    mass: 1\n    inertia: [1,0,0,0,1,0,0,0,1]\n"
         "    elements:\n      - type: Resource\n        uri: square.obj\n"
         "      - type: Resource\n        uri: not_a_mesh.xyz\n"
         "  - type: SubBody\n    uri: sub.body\n    parent: BASE\n";
}

}  // namespace

TEST_CASE("lsp file cache: unchanged meshes and included files are read once, with the same findings") {
  const fs::path dir = bodyfmt::test::fresh_dir("lsp_file_cache");
  for (const char* name : {"square.obj", "square.mtl", "not_a_mesh.xyz"})
    fs::copy_file(fs::path(BODYFMT_TEST_DATA_DIR) / "mesh" / name, dir / name);
  write(dir / "sub.body", kSub);
  const fs::path file = dir / "main.body";
  auto cache = std::make_shared<bodyfmt::FileCache>();

  const std::vector<std::string> first = findings(model(""), file, cache);
  CHECK(first == findings(model(""), file, nullptr));
  const int read = cache->files_read();
  CHECK(read == 3);  // the mesh, the file of an unsupported format, sub.body
  CHECK(findings(model(""), file, cache) == first);
  CHECK(cache->files_read() == read);

  // The mesh's findings are said at the `uri:` of this load.
  const std::string moved = model("  # a line\n  # another\n");
  CHECK(findings(moved, file, cache) == findings(moved, file, nullptr));
  CHECK(cache->files_read() == read);

  // A changed file is read again.
  write(dir / "sub.body", std::string(kSub) + "# longer now\n");
  CHECK(findings(model(""), file, cache) == findings(model(""), file, nullptr));
  CHECK(cache->files_read() == read + 1);
}

TEST_CASE("lsp file cache: caches that share read a file once and hold it while one of them uses it") {
  const fs::path dir = bodyfmt::test::fresh_dir("lsp_file_cache_shared");
  for (const char* name : {"square.obj", "square.mtl", "not_a_mesh.xyz"})
    fs::copy_file(fs::path(BODYFMT_TEST_DATA_DIR) / "mesh" / name, dir / name);
  write(dir / "sub.body", kSub);
  const fs::path file = dir / "main.body";
  const std::string no_meshes =
      "format: ChoreonoidBody\nformat_version: 2.0\nname: M\nroot_link: BASE\nlinks:\n"
      "  - name: BASE\n    joint_type: free\n    mass: 1\n    inertia: [1,0,0,0,1,0,0,0,1]\n"
      "  - type: SubBody\n    uri: sub.body\n    parent: BASE\n";
  const auto root = std::make_shared<bodyfmt::FileCache>();  // holds nothing: no load goes through it
  auto a = root->make_sharing();
  auto b = root->make_sharing();

  const std::vector<std::string> first = findings(model(""), file, a);
  CHECK(a->files_read() == 3);
  CHECK(findings(model(""), file, b) == first);
  CHECK(b->files_read() == 0);  // all three found in what `a` read
  CHECK(root->entries_held() == 0);
  b->forget_unused();  // as bodyls does after each load: this one used all it holds
  CHECK(b->entries_held() == a->entries_held());

  // `b`'s latest load names no mesh: after forget_unused it holds sub.body's text alone.
  const std::vector<std::string> without = findings(no_meshes, file, b);
  b->forget_unused();
  CHECK(b->entries_held() == 1);
  CHECK(findings(no_meshes, file, b) == without);
  CHECK(b->files_read() == 0);

  // Once `a` is gone, nobody holds the meshes: they are read again, sub.body is not.
  a.reset();
  CHECK(findings(model(""), file, b) == first);
  CHECK(b->files_read() == 2);
  // forget_unused keeps what the loads since the last call used.
  b->forget_unused();
  CHECK(findings(model(""), file, b) == first);
  CHECK(b->files_read() == 2);
  // Without forget_unused a cache keeps every file it read.
  CHECK(findings(no_meshes, file, b) == without);
  CHECK(findings(model(""), file, b) == first);
  CHECK(b->files_read() == 2);
}
