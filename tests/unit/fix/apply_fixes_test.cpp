// Fix-its applied to text, the unified diff, and the model comparison behind `bodycheck --fix`.
#include <bodyfmt/fix.h>
#include <bodyfmt/load.h>

#include <doctest/doctest.h>

namespace {

using namespace bodyfmt;

FixIt edit(std::size_t begin, std::string original, std::string replacement) {
  FixIt f;
  f.file = "x.body";
  f.begin = begin;
  f.end = begin + original.size();
  f.line = 1;
  f.column = static_cast<int>(begin) + 1;
  f.original = std::move(original);
  f.replacement = std::move(replacement);
  return f;
}

std::optional<Model> load(const std::string& text) {
  CollectingSink sink;
  LoadOptions options;
  options.load_meshes = false;
  return load_body_string(text, "x.body", options, sink);
}

}  // namespace

TEST_CASE("apply_fixes: edits exact ranges, once per identical edit, and keeps every other byte") {
  const std::string text = "a: jointRange # c\n  b: 'jointRange'\n";
  std::string why;
  auto out = apply_fixes(text,
                         {edit(3, "jointRange", "joint_range"), edit(24, "jointRange", "joint_range"),
                          edit(3, "jointRange", "joint_range")},
                         why);
  REQUIRE(out);
  CHECK(*out == "a: joint_range # c\n  b: 'joint_range'\n");
}

TEST_CASE("apply_fixes: refuses overlapping edits and text that is not there") {
  std::string why;
  CHECK_FALSE(apply_fixes("abcdef", {edit(0, "abc", "x"), edit(2, "cde", "y")}, why));
  CHECK(why.find("overlap") != std::string::npos);
  CHECK_FALSE(apply_fixes("abcdef", {edit(1, "xyz", "q")}, why));
  CHECK(why.find("not there") != std::string::npos);
  CHECK_FALSE(apply_fixes("abc", {edit(2, "cde", "q")}, why));  // past the end
}

TEST_CASE("unified_diff: diff -u hunks with 3 lines of context, split by 7 unchanged lines") {
  std::string before, after;
  for (int i = 1; i <= 20; ++i) {
    before += "l" + std::to_string(i) + "\n";
    after += (i == 2 || i == 17 ? "L" : "l") + std::to_string(i) + "\n";
  }
  // Checked against GNU diff -u 3.8 on the same two texts.
  CHECK(unified_diff(before, after, "f.body") ==
        "--- a/f.body\n+++ b/f.body\n"
        "@@ -1,5 +1,5 @@\n l1\n-l2\n+L2\n l3\n l4\n l5\n"
        "@@ -14,7 +14,7 @@\n l14\n l15\n l16\n-l17\n+L17\n l18\n l19\n l20\n");
  CHECK(unified_diff(before, before, "f.body").empty());
  // An absolute path as git writes it: one slash after a/ and b/.
  CHECK(unified_diff("a\n", "b\n", "/tmp/m/f.body") == "--- a/tmp/m/f.body\n+++ b/tmp/m/f.body\n@@ -1 +1 @@\n-a\n+b\n");
  // Line counts that differ go through the general edit script; a missing final newline is marked.
  CHECK(unified_diff("a\nb\nc", "a\nc\nd\n", "g") ==
        "--- a/g\n+++ b/g\n@@ -1,3 +1,3 @@\n a\n-b\n-c\n\\ No newline at end of file\n+c\n+d\n");
}

TEST_CASE("model_difference: the same model written two ways is equal, a changed number is named") {
  const std::string head = "format: ChoreonoidBody\nformat_version: 1.0\n";
  auto degrees = load(head +
                      "links:\n  - name: R\n    jointType: free\n  - name: J\n    parent: R\n"
                      "    jointType: revolute\n    jointRange: [ -90, 45 ]\n");
  auto radians = load(head +
                      "angle_unit: radian\nlinks:\n  - name: R\n    joint_type: free\n  - name: J\n"
                      "    parent: R\n    joint_type: revolute\n"
                      "    joint_range: [ -1.5707963267948966, 0.7853981633974483 ]\n");
  auto other = load(head +
                    "links:\n  - name: R\n    jointType: free\n  - name: J\n    parent: R\n"
                    "    jointType: revolute\n    jointRange: [ -90, 45.000001 ]\n");
  REQUIRE(degrees);
  REQUIRE(radians);
  REQUIRE(other);
  CHECK_FALSE(model_difference(*degrees, *radians));
  auto difference = model_difference(*degrees, *other);
  REQUIRE(difference);
  // named as bodydiff names the field, with both values (45.000001 deg = 0.78539818085074... rad)
  const std::string expected_head =
      "link \"J\" joint_range: [-1.5707963267948966, 0.7853981633974483] rad = [-90, 45] deg != "
      "[-1.5707963267948966, 0.78539818085074";
  const std::string expected_tail = "] rad = [-90, 45.000001] deg";
  CHECK(difference->compare(0, expected_head.size(), expected_head) == 0);
  CHECK(difference->size() > expected_tail.size());
  CHECK(difference->compare(difference->size() - expected_tail.size(), expected_tail.size(), expected_tail) == 0);
}
