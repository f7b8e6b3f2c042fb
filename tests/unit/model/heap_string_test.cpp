// HeapString: the link strings that most links leave unset (joint_name, actuation_mode,
// contact_material) cost one pointer, and read, compare and copy as std::string does.

#include <bodyfmt/model.h>

#include <doctest/doctest.h>

#include <string>
#include <unordered_map>

using bodyfmt::HeapString;

TEST_CASE("HeapString is one pointer") { CHECK(sizeof(HeapString) == sizeof(void*)); }

TEST_CASE("HeapString reads as the string it holds, empty is unset") {
  HeapString s;
  CHECK(s.empty());
  CHECK(s.str().empty());
  CHECK(s == "");
  s = std::string("ELBOW_JOINT");
  CHECK_FALSE(s.empty());
  CHECK(s == "ELBOW_JOINT");
  CHECK(s != "ELBOW");
  CHECK(std::string("ELBOW_JOINT") == s);
  const std::string& as_string = s;
  CHECK(as_string.size() == 11);
  // Assigning an empty value frees it: empty() and an empty text are the same state.
  s = "";
  CHECK(s.empty());
}

TEST_CASE("HeapString copies are independent, concatenation gives std::string") {
  HeapString a = "torque";
  HeapString b = a;
  b = "velocity";
  CHECK(a == "torque");
  CHECK(b == "velocity");
  HeapString moved = std::move(b);
  CHECK(moved == "velocity");
  const std::string prefixed = std::string("arm_") + a + "_mode";
  CHECK(prefixed == "arm_torque_mode");
  CHECK("\"" + a + "\"" == "\"torque\"");
}

TEST_CASE("HeapString keys a map of string views, as the loader's joint-name index does") {
  HeapString name = "J1";
  std::unordered_map<std::string_view, int> index;
  CHECK(index.emplace(name, 7).second);
  CHECK(index.at("J1") == 7);
}
