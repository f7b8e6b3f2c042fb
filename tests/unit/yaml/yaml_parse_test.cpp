#include "yaml/yaml_node.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

using bodyfmt::CollectingSink;
using bodyfmt::Diagnostic;
using bodyfmt::FixSafety;
using bodyfmt::Severity;
using bodyfmt::SourceLocation;
using namespace bodyfmt::yaml;

namespace {

std::unique_ptr<Document> parse(std::string_view text, CollectingSink& sink, const ParseOptions& options = {}) {
  return parse_yaml(text, "t.yaml", options, sink);
}

SourceLocation at(int line, int column) { return SourceLocation{"t.yaml", line, column}; }

// The value under `key`; fails the test case when absent.
const NodeRef& value_of(const Node& mapping, std::string_view key) {
  const MapEntry* entry = mapping.find(key);
  REQUIRE_MESSAGE(entry != nullptr, "missing key " << key);
  return entry->value;
}

const Diagnostic& only_diagnostic(const CollectingSink& sink, std::string_view rule_id) {
  REQUIRE(sink.diagnostics().size() == 1);
  CHECK(sink.diagnostics()[0].rule_id == rule_id);
  return sink.diagnostics()[0];
}

std::string keys_of(const Node& mapping) {
  std::string keys;
  for (const MapEntry& entry : mapping.entries()) keys += std::string(entry.key) + (entry.merged ? "* " : " ");
  return keys;
}

// `a0: &a0 "lol"`, then `aN: &aN [*aN-1, ... 9 times]` up to a9 (toolchain.md §3).
std::string billion_laughs() {
  std::string text = "a0: &a0 \"lol\"\n";
  for (int level = 1; level <= 9; ++level) {
    std::string previous = "*a" + std::to_string(level - 1);
    text += "a" + std::to_string(level) + ": &a" + std::to_string(level) + " [";
    for (int i = 0; i < 9; ++i) text += (i == 0 ? "" : ", ") + previous;
    text += "]\n";
  }
  return text;
}

std::string nested_sequences(int depth, std::string_view inner) {
  return std::string(depth, '[') + std::string(inner) + std::string(depth, ']');
}

}  // namespace

TEST_CASE("yaml: positions of scalars, sequences, mappings and keys are 1-based") {
  CollectingSink sink;
  auto doc = parse(
      "name: robot\n"
      "links:\n"
      "  - name: base\n"
      "    size: [1, 2, 3]\n"
      "  - {name: arm}\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  REQUIRE(root.is_mapping());
  CHECK(root.location == at(1, 1));
  CHECK(root.entries()[0].key_location == at(1, 1));
  CHECK(value_of(root, "name")->location == at(1, 7));
  CHECK(root.find("links")->key_location == at(2, 1));

  const NodeRef& links = value_of(root, "links");
  REQUIRE(links->is_sequence());
  CHECK(links->location == at(3, 3));
  REQUIRE(links->items().size() == 2);
  const Node& base = *links->items()[0];
  CHECK(base.location == at(3, 5));
  CHECK(value_of(base, "name")->location == at(3, 11));
  CHECK(base.find("size")->key_location == at(4, 5));
  const NodeRef& size = value_of(base, "size");
  CHECK(size->location == at(4, 11));
  REQUIRE(size->items().size() == 3);
  CHECK(size->items()[1]->location == at(4, 15));
  CHECK(size->items()[1]->scalar() == "2");

  const Node& arm = *links->items()[1];
  CHECK(arm.location == at(5, 5));
  CHECK(arm.find("name")->key_location == at(5, 6));
  CHECK(value_of(arm, "name")->location == at(5, 12));
  CHECK(doc->file == "t.yaml");
}

TEST_CASE("yaml: CRLF line ends and a byte order mark do not shift positions") {
  CollectingSink sink;
  auto doc = parse(
      "\xEF\xBB\xBF"
      "a: 1\r\nb:\r\n  - &x ~\r\n  - *x\r\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  CHECK(value_of(*doc->root, "a")->location == at(1, 4));
  const NodeRef& b = value_of(*doc->root, "b");
  REQUIRE(b->items().size() == 2);
  CHECK(b->items()[0]->scalar() == "~");
  CHECK(b->items()[0]->location == at(3, 5));
  CHECK(b->items()[1].node == b->items()[0].node);
  CHECK(b->items()[1].use_site() == at(4, 5));
}

TEST_CASE("yaml: an alias is the anchored node itself and keeps the use site") {
  CollectingSink sink;
  auto doc = parse(
      "base: &b {mass: 1}\n"
      "first: *b\n"
      "second:   *b\n"
      "name: &s 'x'\n"
      "again: *s\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  const NodeRef& base = value_of(root, "base");
  const NodeRef& first = value_of(root, "first");
  const NodeRef& second = value_of(root, "second");
  CHECK(first.node == base.node);
  CHECK(second.node == base.node);
  CHECK(doc->anchor_of(base.node) == "b");
  CHECK(doc->anchors.at("b") == base.node);

  CHECK(base.alias_site == nullptr);
  CHECK(base->location == at(1, 7));  // the anchor's site
  CHECK(base.use_site() == at(1, 7));
  REQUIRE(first.alias_site != nullptr);
  CHECK(*first.alias_site == at(2, 8));
  CHECK(first.use_site() == at(2, 8));
  CHECK(first->location == at(1, 7));
  CHECK(second.use_site() == at(3, 11));

  const NodeRef& again = value_of(root, "again");
  CHECK(again.node == value_of(root, "name").node);
  CHECK(again->scalar() == "x");
  CHECK_FALSE(again->plain);
  CHECK(again.use_site() == at(5, 8));
  CHECK(again->location == at(4, 7));
}

TEST_CASE("yaml: scalars stay strings, with quoting and tags recorded") {
  CollectingSink sink;
  auto doc = parse(
      "joint_axis: Y\n"
      "on: yes\n"
      "mass: 0.t\n"
      "n: 1e3\n"
      "quoted: \"Y\"\n"
      "block: |\n"
      "  text\n"
      "tagged: !!str 12\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  CHECK(value_of(root, "joint_axis")->scalar() == "Y");
  CHECK(value_of(root, "joint_axis")->plain);
  CHECK(value_of(root, "on")->scalar() == "yes");  // the key `on` is a string too
  CHECK(value_of(root, "mass")->scalar() == "0.t");
  CHECK(value_of(root, "n")->scalar() == "1e3");
  CHECK(value_of(root, "quoted")->scalar() == "Y");
  CHECK_FALSE(value_of(root, "quoted")->plain);
  CHECK(value_of(root, "block")->scalar() == "text\n");
  CHECK_FALSE(value_of(root, "block")->plain);
  CHECK(value_of(root, "tagged")->scalar() == "12");
  CHECK(doc->tag_of(value_of(root, "tagged").node) == "!!str");
  CHECK(value_of(root, "tagged")->location == at(8, 9));
  CHECK(doc->tag_of(value_of(root, "n").node).empty());
}

TEST_CASE("yaml: null scalars keep their spelling and quoted ones are not null") {
  CollectingSink sink;
  auto doc = parse(
      "empty:\n"
      "null: 1\n"
      "tilde: ~\n"
      "word: Null\n"
      "quoted: ''\n"
      "text: 'null'\n"
      "list: [~, a]\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  const NodeRef& empty = value_of(root, "empty");
  CHECK(empty->is_null());
  CHECK(empty->scalar().empty());
  // A missing value has no text of its own; it is reported at its key.
  CHECK(empty->location == at(1, 1));
  CHECK(value_of(root, "null")->scalar() == "1");  // `null` as a key is just a string
  CHECK(value_of(root, "tilde")->is_null());
  CHECK(value_of(root, "tilde")->scalar() == "~");
  CHECK(value_of(root, "word")->scalar() == "Null");
  CHECK(value_of(root, "word")->is_null());
  CHECK_FALSE(value_of(root, "quoted")->is_null());
  CHECK_FALSE(value_of(root, "text")->is_null());
  const NodeRef& list = value_of(root, "list");
  REQUIRE(list->items().size() == 2);
  CHECK(list->items()[0]->is_null());
  CHECK(list->items()[0]->location == at(7, 8));
  CHECK_FALSE(list->items()[1]->is_null());
}

TEST_CASE("yaml: merge key - local keys win before and after <<") {
  CollectingSink sink;
  auto doc = parse(
      "base: &base {a: 1, b: 2, c: 3}\n"
      "m:\n"
      "  a: local_a\n"
      "  <<: *base\n"
      "  c: local_c\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& m = *value_of(*doc->root, "m");
  CHECK(keys_of(m) == "a b* c ");  // merged entries take the place of `<<`
  CHECK(value_of(m, "a")->scalar() == "local_a");
  CHECK(value_of(m, "c")->scalar() == "local_c");
  CHECK(value_of(m, "b").node == value_of(*value_of(*doc->root, "base"), "b").node);
  CHECK(m.find("b")->key_location == at(1, 20));
  CHECK(m.find("<<") == nullptr);
  // base {a,b,c} = 4 nodes, m {a,b,c} = 4 nodes, root = 1.
  CHECK(doc->expanded_node_count == 9);
}

TEST_CASE("yaml: merge key - sequence of sources, the first source wins") {
  CollectingSink sink;
  auto doc = parse(
      "x: &x {k: 1}\n"
      "y: &y {k: 2, j: 3}\n"
      "m: {<<: [*x, *y], own: 4}\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& m = *value_of(*doc->root, "m");
  CHECK(keys_of(m) == "k* j* own ");
  CHECK(value_of(m, "k")->scalar() == "1");
  CHECK(value_of(m, "j")->scalar() == "3");
}

TEST_CASE("yaml: merge key - inline source and nested merges") {
  CollectingSink sink;
  auto doc = parse(
      "a: &a {x: 1}\n"
      "b: &b {<<: *a, y: 2}\n"
      "c: {<<: *b, z: 3}\n"
      "d: {<<: {w: 0}, v: 5}\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  const Node& c = *value_of(root, "c");
  CHECK(keys_of(c) == "x* y* z ");
  CHECK(value_of(c, "x")->scalar() == "1");
  CHECK(value_of(c, "x").node == value_of(*value_of(root, "a"), "x").node);
  CHECK(keys_of(*value_of(root, "d")) == "w* v ");
}

TEST_CASE("yaml: merge key - a non-mapping value is an error located at the value") {
  CollectingSink sink;
  auto doc = parse(
      "s: &s 5\n"
      "m: {<<: *s, k: 1}\n"
      "n: {<<: [{a: 1}, 3], k: 2}\n",
      sink);
  REQUIRE(doc);  // the document stays usable
  REQUIRE(sink.diagnostics().size() == 2);
  CHECK(sink.diagnostics()[0].rule_id == "yaml-merge-invalid");
  CHECK(sink.diagnostics()[0].severity == Severity::kError);
  CHECK(sink.diagnostics()[0].location == at(2, 9));  // the alias use site
  CHECK(sink.diagnostics()[1].rule_id == "yaml-merge-invalid");
  CHECK(sink.diagnostics()[1].location == at(3, 18));
  CHECK(keys_of(*value_of(*doc->root, "m")) == "k ");
  CHECK(keys_of(*value_of(*doc->root, "n")) == "a* k ");
}

TEST_CASE("yaml: duplicate key warns, located at the second key, the last one wins") {
  CollectingSink sink;
  auto doc = parse(
      "type: Collision\n"
      "other: 1\n"
      "type: Group\n",
      sink);
  REQUIRE(doc);
  const Diagnostic& d = only_diagnostic(sink, "yaml-duplicate-key");
  CHECK(d.severity == Severity::kWarning);
  CHECK(d.location == at(3, 1));
  CHECK(d.message.find("line 1") != std::string::npos);
  const Node& root = *doc->root;
  CHECK(keys_of(root) == "type other ");
  CHECK(value_of(root, "type")->scalar() == "Group");
  CHECK(root.find("type")->key_location == at(3, 1));
  CHECK(doc->expanded_node_count == 3);
}

TEST_CASE("yaml: duplicate keys in a large mapping (indexed, not scanned) keep the first line") {
  // Mappings of more than 16 keys are checked through a hash index built on the way; a third
  // spelling of a key still names the line of the first.
  std::string text;
  for (int i = 0; i < 40; ++i) text += "k" + std::to_string(i) + ": " + std::to_string(i) + "\n";
  text += "k5: second\nk39: also\nk5: third\n";
  CollectingSink sink;
  auto doc = parse(text, sink);
  REQUIRE(doc);
  REQUIRE(sink.diagnostics().size() == 3);
  CHECK(sink.diagnostics()[0].location == at(41, 1));
  CHECK(sink.diagnostics()[0].message.find("first at line 6)") != std::string::npos);
  CHECK(sink.diagnostics()[1].message.find("first at line 40)") != std::string::npos);
  CHECK(sink.diagnostics()[2].location == at(43, 1));
  CHECK(sink.diagnostics()[2].message.find("first at line 6)") != std::string::npos);
  const Node& root = *doc->root;
  CHECK(root.entries().size() == 40);
  CHECK(value_of(root, "k5")->scalar() == "third");
  CHECK(value_of(root, "k39")->scalar() == "also");
  CHECK(root.entries()[5].key_location == at(43, 1));  // the winning key's site, in file order of the first
}

TEST_CASE("yaml: an anchored key is a node that an alias can use as a value") {
  // Plain keys are not nodes of their own; a key with an anchor must still be one.
  CollectingSink sink;
  auto doc = parse(
      "&k first: 1\n"
      "second: *k\n",
      sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  CHECK(keys_of(root) == "first second ");
  const NodeRef& second = value_of(root, "second");
  CHECK(second->scalar() == "first");
  CHECK(second->location == at(1, 1));
  REQUIRE(second.alias_site != nullptr);
  CHECK(*second.alias_site == at(2, 9));
  CHECK(doc->anchor_of(second.node) == "k");
}

TEST_CASE("yaml: a redefined anchor is an error at the second definition") {
  CollectingSink sink;
  auto doc = parse("a: &x 1\nb: &x 2\n", sink);
  CHECK(doc == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-anchor-redefined");
  CHECK(d.severity == Severity::kError);
  CHECK(d.location == at(2, 4));
  CHECK(d.message.find("line 1") != std::string::npos);
}

TEST_CASE("yaml: an undefined alias is an error at the alias") {
  CollectingSink sink;
  auto doc = parse("a: 1\nb: [1, *nope]\n", sink);
  CHECK(doc == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-undefined-alias");
  CHECK(d.location == at(2, 8));
  CHECK(d.message.find("nope") != std::string::npos);
}

TEST_CASE("yaml: a recursive alias is rejected") {
  CollectingSink sink;
  auto doc = parse("a: &r [1, *r]\n", sink);
  CHECK(doc == nullptr);
  CHECK(only_diagnostic(sink, "yaml-recursive-alias").location == at(1, 11));
}

TEST_CASE("yaml: imported anchors are visible to aliases, local anchors take priority") {
  CollectingSink library_sink;
  auto library = parse("RED: &RED {diffuse: [1, 0, 0]}\nBLUE: &BLUE {diffuse: [0, 0, 1]}\n", library_sink);
  REQUIRE(library);
  ParseOptions options;
  options.imported_anchors = &library->anchors;

  CollectingSink sink;
  auto doc = parse(
      "\xEF\xBB\xBF"  // a byte order mark must not shift the alias sites
      "shape: {appearance: *RED}\n"
      "list: [*RED, *RED, 1]\n"
      "BLUE: &BLUE {diffuse: [0, 1, 0]}\n"
      "local: *BLUE\n",
      sink, options);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const Node& root = *doc->root;
  const NodeRef& appearance = value_of(*value_of(root, "shape"), "appearance");
  CHECK(appearance.node == library->anchors.at("RED"));
  CHECK(appearance.use_site() == at(1, 21));
  const NodeRef& list = value_of(root, "list");
  REQUIRE(list->items().size() == 3);
  CHECK(list->items()[1].node == library->anchors.at("RED"));
  CHECK(list->items()[1].use_site() == at(2, 14));
  CHECK(list->items()[2]->scalar() == "1");
  CHECK(value_of(root, "local").node == value_of(root, "BLUE").node);
  CHECK(value_of(root, "local").node != library->anchors.at("BLUE"));
  CHECK(doc->anchors.count("RED") == 0);

  CollectingSink missing;
  CHECK(parse("a: *GREEN\n", missing, options) == nullptr);
  CHECK(only_diagnostic(missing, "yaml-undefined-alias").location == at(1, 4));
}

TEST_CASE("yaml: a syntax error is fatal and located") {
  CollectingSink sink;
  CHECK(parse("a: b: c\n", sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.severity == Severity::kFatal);
  CHECK(d.location == at(1, 5));
  CHECK(d.message.find("line 1") == std::string::npos);  // no duplicated position prefix

  CollectingSink flow;
  CHECK(parse("a: [1, 2\n", flow) == nullptr);
  CHECK(only_diagnostic(flow, "yaml-syntax").location == at(2, 1));
}

TEST_CASE("yaml: columns count bytes in multi-byte text, bad UTF-8 is a located syntax error") {
  // libyaml's marks count characters; the toolchain's columns count bytes (as before).
  CollectingSink sink;
  auto doc = parse("a: \"\xC3\xA9\xC3\xA9\"\nb: [\xC3\xA9, 1]\n", sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const NodeRef& b = value_of(*doc->root, "b");
  REQUIRE(b->items().size() == 2);
  CHECK(b->items()[0]->scalar() == "\xC3\xA9");
  CHECK(b->items()[1]->location == at(2, 9));

  CollectingSink alias;
  CHECK(parse("a: [\xC3\xA9, *x]\n", alias) == nullptr);
  CHECK(only_diagnostic(alias, "yaml-undefined-alias").location == at(1, 9));

  CollectingSink bad;
  CHECK(parse("a: 1\nc: \xFF\n", bad) == nullptr);
  CHECK(only_diagnostic(bad, "yaml-syntax").location == at(2, 4));
}

TEST_CASE("yaml: a tab inside a flow sequence is accepted") {
  // WAREC1.body writes `[ 0.045, 0.084, 0.0058<TAB>]` (body-format-spec §1.10).
  CollectingSink sink;
  auto doc = parse("translation: [ 0.045, 0.084, 0.0058\t]\nnext:\t[1,\t2]\n", sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  const NodeRef& translation = value_of(*doc->root, "translation");
  REQUIRE(translation->items().size() == 3);
  CHECK(translation->items()[2]->scalar() == "0.0058");
  CHECK(value_of(*doc->root, "next")->items().size() == 2);
}

TEST_CASE("yaml: empty and complex keys are errors, the rest of the mapping is kept") {
  CollectingSink sink;
  auto doc = parse("\"\": 1\n? [a, b]\n: 2\nok: 3\n", sink);
  REQUIRE(doc);
  REQUIRE(sink.diagnostics().size() == 2);
  CHECK(sink.diagnostics()[0].rule_id == "yaml-empty-key");
  CHECK(sink.diagnostics()[0].location == at(1, 1));
  CHECK(sink.diagnostics()[1].rule_id == "yaml-complex-key");
  CHECK(sink.diagnostics()[1].location == at(2, 3));
  CHECK(keys_of(*doc->root) == "ok ");
  CHECK(doc->expanded_node_count == 2);  // dropped keys and values are not counted
}

TEST_CASE("yaml: an empty document gives a null root, only the first document is read") {
  for (std::string_view text : {"", "# only a comment\n"}) {
    CollectingSink sink;
    auto doc = parse(text, sink);
    REQUIRE(doc);
    CHECK(sink.diagnostics().empty());
    REQUIRE(doc->root);
    CHECK(doc->root->is_null());
  }
  CollectingSink sink;
  auto doc = parse("a: 1\n---\nb: [\n", sink);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  CHECK(keys_of(*doc->root) == "a ");
}

// Time and memory are measured in bench/billion_laughs.sh, not asserted here.
TEST_CASE("yaml: billion laughs is rejected at the crossing alias, before any expansion") {
  const std::string text = billion_laughs();
  CHECK(text.size() < 1024);
  CollectingSink sink;
  auto doc = parse(text, sink);
  CHECK(doc == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-alias-expansion");
  CHECK(d.severity == Severity::kFatal);
  // Nodes before a8 (root, a0..a7): 1 + 6,053,444; a8 itself +1; each *a7 adds a7's 5,380,840
  // nodes: after six 38,338,486, and the seventh (column 10 + 6 * 5) passes the default limit
  // of 40,000,000.
  CHECK(d.location == at(9, 40));
  CHECK(d.message.find("40000000") != std::string::npos);
  CHECK_FALSE(d.fix_hint.empty());
}

TEST_CASE("yaml: the 9x9 alias bomb is measured exactly when the limit allows it") {
  // A node counts once per appearance: a scalar is 1, a collection 1 + its children, and
  // mapping keys are not nodes. a0 = 1, aN = 1 + 9 a(N-1) = (9^(N+1) - 1) / 8, so a9 =
  // 435,848,050, and the sum a0..a9 = ((9^11 - 9) / 8 - 10) / 8 = 490,329,055. The root mapping
  // adds 1: 490,329,056. toolchain.md §3 reports 490,329,066 because it also counts the ten
  // key scalars.
  ParseOptions options;
  options.max_expanded_nodes = 490'329'056;
  CollectingSink sink;
  auto doc = parse(billion_laughs(), sink, options);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  CHECK(doc->expanded_node_count == 490'329'056);
  CHECK(value_of(*doc->root, "a9")->expanded_size == 435'848'050);
  CHECK(value_of(*doc->root, "a9")->expanded_depth == 9);

  options.max_expanded_nodes = 490'329'055;
  CollectingSink over;
  CHECK(parse(billion_laughs(), over, options) == nullptr);
  CHECK(only_diagnostic(over, "yaml-alias-expansion").location == at(10, 50));  // the last *a8
}

TEST_CASE("yaml: nesting deeper than max_depth is fatal, counted through aliases") {
  ParseOptions options;
  options.max_depth = 10;
  CollectingSink ok_sink;
  // The root mapping is level 1, so ten levels fit: 1 + 9 brackets.
  CHECK(parse("a: " + nested_sequences(9, "x") + "\n", ok_sink, options) != nullptr);
  CHECK(ok_sink.diagnostics().empty());

  CollectingSink deep;
  CHECK(parse("a: " + nested_sequences(10, "x") + "\n", deep, options) == nullptr);
  const Diagnostic& d = only_diagnostic(deep, "yaml-depth");
  CHECK(d.severity == Severity::kFatal);
  CHECK(d.location == at(1, 13));

  // *a is 6 levels deep; used 1 + 3 levels down it reaches 10, 1 + 4 levels down 11.
  const std::string six = "a: &a " + nested_sequences(6, "x") + "\n";
  CollectingSink fits;
  CHECK(parse(six + "b: " + nested_sequences(3, "*a") + "\n", fits, options) != nullptr);
  CHECK(fits.diagnostics().empty());
  CollectingSink through_alias;
  CHECK(parse(six + "b: " + nested_sequences(4, "*a") + "\n", through_alias, options) == nullptr);
  CHECK(only_diagnostic(through_alias, "yaml-depth").location == at(2, 8));

  // The parser's fixed nesting ceiling (500) is reported the same way.
  options.max_depth = 100'000;
  CollectingSink guard;
  CHECK(parse(nested_sequences(600, ""), guard, options) == nullptr);
  CHECK(only_diagnostic(guard, "yaml-depth").severity == Severity::kFatal);
}

TEST_CASE("yaml: every corpus .body and .yaml file parses without errors") {
  const std::filesystem::path corpus = BODYFMT_SHARED_DIR "/corpus/choreonoid";
  REQUIRE(std::filesystem::is_directory(corpus));
  int files = 0;
  int warnings = 0;
  for (const auto& item : std::filesystem::recursive_directory_iterator(corpus)) {
    const std::string extension = item.path().extension().string();
    if (!item.is_regular_file() || (extension != ".body" && extension != ".yaml")) continue;
    std::ifstream in(item.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    CollectingSink sink;
    auto doc = parse_yaml(text.str(), item.path().string(), ParseOptions{}, sink);
    CHECK_MESSAGE(doc != nullptr, item.path());
    CHECK_MESSAGE(sink.error_count() == 0, item.path());
    warnings += sink.count(Severity::kWarning);
    ++files;
  }
  MESSAGE(files << " corpus files parsed, " << warnings << " warnings");
  CHECK(files > 50);
}

namespace {

// Takes the items of `key` whose first scalar is not "keep".
class TakeItems : public SequenceConsumer {
 public:
  std::string_view key() const override { return "items"; }
  bool begin(const Node& head, const Node&) override {
    head_keys = keys_of(head);
    return true;
  }
  bool take(const NodeRef& item) override {
    if (item->is_scalar() && item->scalar() == "keep") return false;
    taken.push_back(item->is_scalar() ? std::string(item->scalar()) : std::string(item->items().front()->scalar()));
    return true;
  }
  std::string head_keys;
  std::vector<std::string> taken;
};

}  // namespace

TEST_CASE("yaml: a SequenceConsumer takes the items of its key while they are parsed") {
  const std::string text = "a: 1\nb: &b [x]\nitems:\n  - one\n  - keep\n  - [two, *b]\n  - &c three\nafter: *c\n";
  CollectingSink plain_sink, sink;
  auto plain = parse(text, plain_sink);
  TakeItems consumer;
  ParseOptions options;
  options.stream = &consumer;
  auto doc = parse(text, sink, options);
  REQUIRE(doc);
  CHECK(sink.diagnostics().empty());
  CHECK(consumer.head_keys == "a b ");
  CHECK(consumer.taken == std::vector<std::string>{"one", "two", "three"});
  // What was declined stays, in order; the sizes still count every item.
  const NodeRef& items = value_of(*doc->root, "items");
  REQUIRE(items->items().size() == 1);
  CHECK(items->items()[0]->scalar() == "keep");
  CHECK(doc->expanded_node_count == plain->expanded_node_count);
  CHECK(items->expanded_size == value_of(*plain->root, "items")->expanded_size);
  // An anchor defined in a taken item is still there for a later alias.
  CHECK(value_of(*doc->root, "after")->scalar() == "three");
}

TEST_CASE("yaml: what a SequenceConsumer throws reaches the caller, not a YAML error") {
  struct Throwing : SequenceConsumer {
    std::string_view key() const override { return "items"; }
    bool begin(const Node&, const Node&) override { return true; }
    bool take(const NodeRef&) override { throw std::logic_error("consumer invariant"); }
  } consumer;
  ParseOptions options;
  options.stream = &consumer;
  CollectingSink sink;
  CHECK_THROWS_AS(parse("items: [a]\n", sink, options), std::logic_error);
  CHECK(sink.diagnostics().empty());
}

// Issue 40: a syntax error in the words of someone editing by hand, at the line to change, with
// libyaml's words (the parser's state) kept as the note.
TEST_CASE("yaml: a line indented less than its siblings is named, libyaml's words are the note") {
  CollectingSink sink;
  CHECK(parse("links:\n  - name: A\n    mass: 1\n   inertia: [1, 0, 0, 1, 0, 1]\n    parent: B\n", sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.location == at(4, 4));
  CHECK(d.message ==
        "line 4 is indented 3 spaces, which lines up with no line above it; the keys it follows (line 3) are "
        "indented 4: the keys of one mapping start in the same column");
  CHECK(d.fix_hint.rfind("libyaml: did not find expected", 0) == 0);
}

TEST_CASE("yaml: a line indented more than the value above it is named") {
  CollectingSink sink;
  CHECK(parse("links:\n  - name: A\n    mass: 1\n     inertia: [1, 0, 0, 1, 0, 1]\n", sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.location == at(4, 6));
  CHECK(d.message ==
        "line 4 is indented 5 spaces, more than line 3 above it (4): the keys of one mapping start in the same column");
  CHECK(d.fix_hint.rfind("libyaml: mapping values are not allowed", 0) == 0);
}

TEST_CASE("yaml: a top-level key indented by one space and a misaligned list item are named") {
  CollectingSink top;
  CHECK(parse("format: x\nlinks:\n  - name: A\n    mass: 1\n elements: []\n", top) == nullptr);
  CHECK(only_diagnostic(top, "yaml-syntax").location == at(5, 2));
  CHECK(only_diagnostic(top, "yaml-syntax").message.find("indented 1 space,") != std::string::npos);
  CollectingSink item;
  CHECK(parse("links:\n  - name: A\n    elements:\n      - type: Shape\n     - type: Shape\n", item) == nullptr);
  CHECK(only_diagnostic(item, "yaml-syntax").location == at(5, 6));
  CHECK(only_diagnostic(item, "yaml-syntax").message.find("are indented 6") != std::string::npos);
}

TEST_CASE("yaml: a tab in an indentation is named at the tab") {
  CollectingSink sink;
  CHECK(parse("links:\n  - name: A\n\tmass: 1\n", sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.location == at(3, 1));
  CHECK(d.message == "a tab in the indentation of line 3: YAML indents with spaces only; replace the tab with spaces");
  CHECK(d.fix_hint.rfind("libyaml: ", 0) == 0);
  CollectingSink after_spaces;
  CHECK(parse("links:\n  - name: A\n    mass: 1\n  \tparent: x\n", after_spaces) == nullptr);
  CHECK(only_diagnostic(after_spaces, "yaml-syntax").location == at(4, 3));
}

TEST_CASE("yaml: an error that is not about indentation keeps libyaml's words") {
  CollectingSink sink;
  CHECK(parse("a: 1\nb: [c, d\ne: f\n", sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.message.find("did not find expected") != std::string::npos);
  CHECK(d.fix_hint.empty());
  CHECK(d.fixes.empty());
}

// Issue 47: the typo of Choreonoid's own tutorial, `type: RigidBody:`, gave libyaml's "mapping
// values are not allowed in this context". It is explained at the colon, with its removal as
// an (unsafe) fix-it; libyaml's words stay in the hint.
TEST_CASE("yaml: a value ending with ':' is explained at the colon, with the edit that removes it") {
  const std::string text = "links:\n  - name: A\n    elements:\n      -\n        type: RigidBody:\n        mass: 1\n";
  CollectingSink sink;
  CHECK(parse(text, sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.severity == Severity::kFatal);
  CHECK(d.location == at(5, 24));  // the colon
  CHECK(d.message.find("a value cannot end with ':'") != std::string::npos);
  CHECK(d.message.find("write \"type: RigidBody\"") != std::string::npos);
  CHECK(d.fix_hint.find("libyaml: mapping values are not allowed") != std::string::npos);
  REQUIRE(d.fixes.size() == 1);
  CHECK(d.fixes[0].safety == FixSafety::kUnsafe);
  CHECK(d.fixes[0].original == ":");
  CHECK(text.substr(d.fixes[0].begin, d.fixes[0].end - d.fixes[0].begin) == ":");
  CHECK(d.fixes[0].begin == text.find("RigidBody:") + 9);
  CHECK(d.fixes[0].replacement.empty());
  // After a list item's dash, with a comment after the colon, and with CRLF line ends.
  for (const char* variant : {"links:\n  - type: RigidBody:   # note\n", "links:\r\n  - type: RigidBody:\r\n"}) {
    CAPTURE(variant);
    CollectingSink other;
    CHECK(parse(variant, other) == nullptr);
    const Diagnostic& o = only_diagnostic(other, "yaml-syntax");
    CHECK(o.location == at(2, 20));
    CHECK(o.message.find("a value cannot end with ':'") != std::string::npos);
    CHECK(o.fixes.size() == 1);
  }
}

TEST_CASE("yaml: a plain value holding ': ' is explained: quote it") {
  CollectingSink sink;
  CHECK(parse("a: 1\nb: c: d  # x\n", sink) == nullptr);
  const Diagnostic& d = only_diagnostic(sink, "yaml-syntax");
  CHECK(d.location == at(2, 5));
  CHECK(d.message.find("quote the value: b: \"c: d\"") != std::string::npos);
  CHECK(d.fixes.empty());
}
