// LinkSources keeps a line and column per field and the link's file once; a field written in
// another file (a SubBody node's override) keeps its own file.

#include <bodyfmt/model.h>

#include <doctest/doctest.h>

using bodyfmt::LinkSources;
using bodyfmt::SourceLocation;

TEST_CASE("LinkSources: an unset field is unknown and names no file") {
  const LinkSources s;
  CHECK_FALSE(s.mass().known());
  CHECK(s.mass().file.empty());
  CHECK(s.mass().column == 0);
}

TEST_CASE("LinkSources: fields read back as set, in one file or several") {
  LinkSources s;
  s.set(LinkSources::kName, SourceLocation{"robot.body", 7, 11});
  s.set(LinkSources::kMass, SourceLocation{"robot.body", 12, 5});
  CHECK(s.name() == SourceLocation{"robot.body", 7, 11});
  CHECK(s.mass() == SourceLocation{"robot.body", 12, 5});
  // An override from the includer, then one from a third file.
  s.set(LinkSources::kTranslation, SourceLocation{"includer.body", 14, 18});
  s.set(LinkSources::kRotation, SourceLocation{"outer.body", 3, 9});
  CHECK(s.translation() == SourceLocation{"includer.body", 14, 18});
  CHECK(s.rotation() == SourceLocation{"outer.body", 3, 9});
  CHECK(s.name() == SourceLocation{"robot.body", 7, 11});
  // Set again in the link's own file, and to a location without a file.
  s.set(LinkSources::kTranslation, SourceLocation{"robot.body", 8, 3});
  s.set(LinkSources::kRotation, SourceLocation{"", 2, 1});
  CHECK(s.translation() == SourceLocation{"robot.body", 8, 3});
  CHECK(s.rotation() == SourceLocation{"", 2, 1});
  CHECK(s.rotation().file.empty());
  CHECK_FALSE(s.inertia().known());
  CHECK(s.inertia().file.empty());
}

TEST_CASE("LinkSources: copies are independent") {
  LinkSources a;
  a.set(LinkSources::kJointRange, SourceLocation{"a.body", 4, 2});
  a.set(LinkSources::kJointAxis, SourceLocation{"b.body", 5, 3});
  LinkSources b = a;
  b.set(LinkSources::kJointAxis, SourceLocation{"c.body", 6, 4});
  CHECK(a.joint_axis() == SourceLocation{"b.body", 5, 3});
  CHECK(b.joint_axis() == SourceLocation{"c.body", 6, 4});
  CHECK(b.joint_range() == SourceLocation{"a.body", 4, 2});
  a = b;
  CHECK(a.joint_axis() == SourceLocation{"c.body", 6, 4});
}
