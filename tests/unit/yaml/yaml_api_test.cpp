// The public YAML API (bodyfmt/yaml.h), through the public header only: walking a document,
// located reads of scalars, the did-you-mean for unknown keys, and the bounded file reader
// that refuses devices, FIFOs, folders and files over the limit before reading them.
#include <bodyfmt/yaml.h>
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace bodyfmt;

namespace {

const Diagnostic& only(const CollectingSink& sink) {
  REQUIRE(sink.diagnostics().size() == 1);
  return sink.diagnostics()[0];
}

}  // namespace

TEST_CASE("yaml api: a document is walked with every node located, aliases at their use site") {
  CollectingSink sink;
  const std::optional<YamlDocument> doc =
      parse_yaml_text("a: 1\nlist: [x, &k {n: 2}]\nref: *k\nempty:\n", "t.yaml", sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  CHECK(doc->file() == "t.yaml");
  const YamlNode root = doc->root();
  REQUIRE(root.is_mapping());
  const std::vector<YamlEntry> entries = root.entries();
  REQUIRE(entries.size() == 4);
  CHECK(entries[0].key == "a");
  CHECK(entries[0].key_location == SourceLocation{"t.yaml", 1, 1});
  CHECK(entries[0].value.scalar() == "1");
  CHECK(entries[0].value.location() == SourceLocation{"t.yaml", 1, 4});
  const std::vector<YamlNode> items = entries[1].value.items();
  REQUIRE(items.size() == 2);
  CHECK(items[0].scalar() == "x");
  CHECK(items[1].is_mapping());
  CHECK(items[1].location() == SourceLocation{"t.yaml", 2, 11});
  const std::optional<YamlEntry> ref = root.find("ref");
  REQUIRE(ref);
  CHECK(ref->value.is_mapping());
  CHECK(ref->value.location() == SourceLocation{"t.yaml", 3, 6});  // the alias, not the anchor
  CHECK(ref->value.find("n")->value.scalar() == "2");
  CHECK(root.find("empty")->value.is_null());
  CHECK(!root.find("absent"));
  CHECK(!items[0].find("x"));       // not a mapping
  CHECK(items[0].items().empty());  // not a sequence
  CHECK(root.scalar().empty());     // not a scalar
  CHECK(!YamlNode());               // nothing
  CHECK(YamlNode().location().line == 0);
}

TEST_CASE("yaml api: the YAML layer's findings and limits are the model loader's") {
  CollectingSink sink;
  CHECK(!parse_yaml_text("a: [1\n", "t.yaml", sink));
  CHECK(sink.error_count() == 1);
  CHECK(sink.diagnostics()[0].location.file == "t.yaml");

  CollectingSink duplicate;
  const std::optional<YamlDocument> doc = parse_yaml_text("a: 1\na: 2\n", "t.yaml", duplicate);
  REQUIRE(doc);  // a warning leaves the document usable; the last value wins, as in Choreonoid
  CHECK(duplicate.has("yaml-duplicate-key"));
  CHECK(doc->root().find("a")->value.scalar() == "2");

  CollectingSink deep;
  YamlLimits limits;
  limits.max_depth = 3;
  CHECK(!parse_yaml_text("a: [[[[1]]]]\n", "t.yaml", deep, limits));
  CHECK(deep.error_count() > 0);

  CollectingSink empty;
  const std::optional<YamlDocument> nothing = parse_yaml_text("# only a comment\n", "t.yaml", empty);
  REQUIRE(nothing);
  CHECK(nothing->root().is_null());
}

TEST_CASE("yaml api: YamlReader reads scalars and reports each problem at the value, with one rule id") {
  CollectingSink parse;
  const std::optional<YamlDocument> doc = parse_yaml_text(
      "n: 1.5e-3\nbad: 1.5x\ninf: .inf\nb: yes\nnotb: maybe\nm: {k: v}\ns: [1]\nt: text\n", "r.yaml", parse);
  REQUIRE(doc);
  const YamlNode root = doc->root();
  auto value = [&](const char* key) { return root.find(key)->value; };

  CollectingSink sink;
  YamlReader r(sink, "dynamics-scenario");
  CHECK(r.ok());
  CHECK(r.number(value("n"), "'n'") == 1.5e-3);
  CHECK(r.boolean(value("b"), "'b'") == true);
  CHECK(r.mapping(value("m"), "'m'"));
  CHECK(r.sequence(value("s"), "'s'"));
  CHECK(r.scalar(value("t"), "'t'") == std::string_view("text"));
  CHECK(sink.diagnostics().empty());
  CHECK(r.ok());

  auto expect = [&](auto result, int line, int column, const std::string& message) {
    CHECK(!result);
    const Diagnostic& d = only(sink);
    CHECK(d.rule_id == "dynamics-scenario");
    CHECK(d.severity == Severity::kError);
    CHECK(d.location == SourceLocation{"r.yaml", line, column});
    CHECK(d.message == message);
    sink.clear();
  };
  expect(r.number(value("bad"), "'bad'"), 2, 6, "'bad' must be a number");
  expect(r.number(value("inf"), "'inf'"), 3, 6, "'inf' must be a number");  // finite only
  expect(r.number(value("m"), "'m'"), 6, 4, "'m' must be a number");
  expect(r.boolean(value("notb"), "'notb'"), 5, 7, "'notb' must be true or false");
  expect(r.mapping(value("s"), "'s'"), 7, 4, "'s' must be a mapping");
  expect(r.sequence(value("m"), "'m'"), 6, 4, "'m' must be a list");
  expect(r.scalar(value("s"), "'s'"), 7, 4, "'s' must be a single value, not a list or a mapping");
  CHECK(!r.ok());
}

TEST_CASE("yaml api: unknown keys are reported at the key, with a did-you-mean for a plausible typo") {
  CollectingSink parse;
  const std::optional<YamlDocument> doc = parse_yaml_text("duration: 1\ndurtaion: 2\nzzz: 3\n", "k.yaml", parse);
  REQUIRE(doc);
  CollectingSink sink;
  YamlReader r(sink, "config-invalid");
  CHECK(!r.known_keys(doc->root(), {"duration", "sample"}, "a scenario"));
  REQUIRE(sink.diagnostics().size() == 2);
  CHECK(sink.diagnostics()[0].location == SourceLocation{"k.yaml", 2, 1});
  CHECK(sink.diagnostics()[0].message == "unknown key 'durtaion' in a scenario; did you mean 'duration'?");
  CHECK(sink.diagnostics()[0].fix_hint == "keys: duration, sample");
  CHECK(sink.diagnostics()[1].location == SourceLocation{"k.yaml", 3, 1});
  CHECK(sink.diagnostics()[1].message == "unknown key 'zzz' in a scenario");

  const std::vector<YamlEntry> unknown = unknown_keys(doc->root(), {"duration", "zzz"});
  REQUIRE(unknown.size() == 1);
  CHECK(unknown[0].key == "durtaion");
  CHECK(did_you_mean("smaple", {"duration", "sample"}) == "sample");
  CHECK(did_you_mean("xyz", {"duration", "sample"}).empty());

  CollectingSink clean;
  YamlReader all_known(clean, "config-invalid");
  CHECK(all_known.known_keys(doc->root(), {"duration", "durtaion", "zzz"}, "a scenario"));
  CHECK(clean.diagnostics().empty());
}

TEST_CASE("yaml api: read_yaml_file reads regular files only, within the size limit, and says why not") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("bodyfmt_yaml_api_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path good = dir / "good.yaml";
  std::ofstream(good) << "k: v\n";

  CollectingSink sink;
  const std::optional<YamlDocument> doc = read_yaml_file(good.string(), sink);
  REQUIRE(doc);
  CHECK(doc->root().find("k")->value.location() == SourceLocation{good.string(), 1, 4});

  auto refused = [&](const std::string& path, const YamlLimits& limits, std::string_view what,
                     const std::string& message) {
    CollectingSink errors;
    CHECK(!read_yaml_file(path, errors, limits, what));
    const Diagnostic& d = only(errors);
    CHECK(d.rule_id == "io-read");
    CHECK(d.severity == Severity::kFatal);
    CHECK(d.location == SourceLocation{path, 0, 0});
    CHECK(d.message == message);
  };
  refused("/dev/zero", {}, "", "cannot read \"/dev/zero\": is not a regular file (a device, a FIFO or a socket)");
  const fs::path fifo = dir / "fifo.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // no writer: opening it would block
  refused(fifo.string(), {}, "the scenario",
          "cannot read the scenario: is not a regular file (a device, a FIFO or a socket)");
  refused(dir.string(), {}, "", "cannot read \"" + dir.string() + "\": is a directory, not a file");
  refused((dir / "missing.yaml").string(), {}, "",
          "cannot read \"" + (dir / "missing.yaml").string() + "\": no such file");
  YamlLimits small;
  small.max_file_bytes = 4;
  refused(good.string(), small, "",
          "cannot read \"" + good.string() +
              "\": is 5 bytes, larger than the limit of 4 bytes (LoadOptions::max_file_bytes, --max-file-size)");
  fs::remove_all(dir);
}
