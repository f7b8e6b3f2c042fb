// load/name_index.h against std::map on the same names: every name found with its first index,
// duplicates refused, absent names not found, through several growths of the table.

#include "load/name_index.h"

#include <doctest/doctest.h>

#include <map>
#include <string>
#include <vector>

using bodyfmt::LinkIndex;
using bodyfmt::detail::NameIndex;

TEST_CASE("NameIndex: same answers as std::map, with duplicates and growth") {
  std::vector<std::string> names;
  for (int i = 0; i < 5000; ++i) names.push_back("L" + std::to_string(i % 3700));  // 1300 repeats
  names.push_back("");
  names.push_back("a longer name than the short string buffer holds");
  for (std::size_t expected : {std::size_t{0}, names.size()}) {
    CAPTURE(expected);
    NameIndex index(expected);
    std::map<std::string, LinkIndex> reference;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const auto it = reference.find(names[i]);
      const std::optional<LinkIndex> first = index.insert(names[i], static_cast<LinkIndex>(i));
      if (it == reference.end()) {
        CHECK_FALSE(first.has_value());
        reference.emplace(names[i], static_cast<LinkIndex>(i));
      } else {
        REQUIRE(first.has_value());
        CHECK(*first == it->second);
      }
    }
    CHECK(index.names().size() == reference.size());
    CHECK(index.names().size() == 3702);
    for (const auto& [name, i] : reference) {
      const std::optional<LinkIndex> found = index.find(name);
      REQUIRE(found.has_value());
      CHECK(*found == i);
    }
    CHECK(index.names()[1] == "L1");
    CHECK_FALSE(index.find("L3700").has_value());
    CHECK_FALSE(index.find("l1").has_value());
  }
}
