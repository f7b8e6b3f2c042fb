// The text utilities below the loader and the diagnostics (libbodyfmt/src/text).
#include "text/text_util.h"

#include <doctest/doctest.h>

using namespace bodyfmt::text;

TEST_CASE("text: edit distance is case-insensitive and counts an adjacent transposition once") {
  CHECK(edit_distance("jointRnage", "jointRange") == 1);
  CHECK(edit_distance("MASS", "mass") == 0);
  CHECK(edit_distance("shinines", "shininess") == 1);
  CHECK(edit_distance("abc", "") == 3);
  CHECK(edit_distance("kitten", "sitting") == 3);
}

TEST_CASE("text: suggest allows 1 edit from 4 characters and 2 from 8, nothing below 4") {
  const std::vector<std::string_view> keys = {"mass", "inertia", "center_of_mass", "joint_type"};
  CHECK(suggest("mas", keys).empty());  // 3 characters: too ambiguous
  CHECK(suggest("masz", keys) == "mass");
  CHECK(suggest("inretia", keys) == "inertia");
  CHECK(suggest("joint_tpye", keys) == "joint_type");
  CHECK(suggest("jiont_tpye", keys) == "joint_type");  // 2 edits, 10 characters
  CHECK(suggest("colour", keys).empty());
}

TEST_CASE("text: nearest gives every candidate at the smallest plausible distance, in order") {
  const std::vector<std::string_view> links = {"ARM_R", "CHASSIS", "ARM_L", "chassis2", "TURRET"};
  CHECK(nearest("CHASIS", links) == std::vector<std::string_view>{"CHASSIS"});
  CHECK(nearest("ARM_X", links) == std::vector<std::string_view>{"ARM_R", "ARM_L"});
  CHECK(nearest("arm_l", links) == std::vector<std::string_view>{"ARM_L"});  // 0 beats 1
  CHECK(nearest("TURET", links) == std::vector<std::string_view>{"TURRET"});
  CHECK(nearest("BASE", links).empty());
  CHECK(nearest("ARM", {"ARX", "ARM_L"}).empty());  // 3 characters: too ambiguous
}

TEST_CASE("text: the boolean words are exactly YAML 1.1's, in three cases") {
  for (const char* word : {"y", "Y", "yes", "Yes", "YES", "true", "True", "TRUE", "on", "On", "ON"})
    CHECK(parse_bool_word(word) == true);
  for (const char* word : {"n", "N", "no", "No", "NO", "false", "False", "FALSE", "off", "Off", "OFF"})
    CHECK(parse_bool_word(word) == false);
  for (const char* word : {"yEs", "1", "0", "", "true ", "tRUE"}) CHECK_FALSE(parse_bool_word(word).has_value());
}

TEST_CASE("text: lines split on LF and CRLF without the breaks, no empty last line") {
  CHECK(split_lines("a\nb\r\nc") == std::vector<std::string>{"a", "b", "c"});
  CHECK(split_lines("a\n") == std::vector<std::string>{"a"});
  CHECK(split_lines("\n\n") == std::vector<std::string>{"", ""});
  CHECK(split_lines("").empty());
}

TEST_CASE("text: JSON quoting escapes control characters and keeps valid UTF-8") {
  CHECK(json_quote("plain") == "\"plain\"");
  CHECK(json_quote("a\"b\\c\nd\te\x01") == "\"a\\\"b\\\\c\\nd\\te\\u0001\"");
  CHECK(json_quote("\xC3\xA9\xE2\x80\xA2") == "\"\xC3\xA9\xE2\x80\xA2\"");  // valid UTF-8 kept
  CHECK(json_quote("x\xFFy") == "\"x\\ufffdy\"");                           // invalid byte replaced
  CHECK(json_quote("\xC3") == "\"\\ufffd\"");                               // truncated sequence
}
