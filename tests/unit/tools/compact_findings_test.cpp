// bodycheck's compact findings store (tools/common/compact_findings.h): every field of every
// finding comes back as reported, in order, across text blocks and interned parts.
#include "compact_findings.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using namespace bodyfmt;

namespace {

Diagnostic finding(int i) {
  Diagnostic d;
  d.severity = static_cast<Severity>(i % 4);
  d.rule_id = i % 3 == 0 ? "inertia-implausible" : i % 3 == 1 ? "export-loss" : "";
  d.category = i % 5 == 0 ? "devices" : "";
  d.message = i % 7 == 0 ? std::string() : "link \"L" + std::to_string(i) + "\" " + std::string(i % 300, 'x');
  d.location = SourceLocation{i % 2 ? "a.body" : "b.body", i + 1, i % 80 + 1};
  // Runs of equal hints per rule, a varying one, and none.
  d.fix_hint = i % 11 == 0 ? "" : i % 13 == 0 ? "hint " + std::to_string(i) : "the same hint";
  if (i % 17 == 0) d.via = SourceLocation{"c.body", 2 * i + 1, 3};
  if (i % 19 == 0) {
    FixIt fix;
    fix.file = "a.body";
    fix.begin = static_cast<std::size_t>(i);
    fix.end = static_cast<std::size_t>(i) + 3;
    fix.line = i;
    fix.column = 4;
    fix.original = "abc";
    fix.replacement = "xyz" + std::to_string(i);
    fix.safety = FixSafety::kUpgrade;
    d.fixes.push_back(fix);
  }
  return d;
}

void check_same(const Diagnostic& a, const Diagnostic& b) {
  CHECK(a.severity == b.severity);
  CHECK(a.rule_id == b.rule_id);
  CHECK(a.category == b.category);
  CHECK(a.message == b.message);
  CHECK(a.location == b.location);
  CHECK(a.fix_hint == b.fix_hint);
  CHECK(a.via.has_value() == b.via.has_value());
  if (a.via && b.via) CHECK(*a.via == *b.via);
  REQUIRE(a.fixes.size() == b.fixes.size());
  for (std::size_t k = 0; k < a.fixes.size(); ++k) {
    CHECK(a.fixes[k] == b.fixes[k]);
    CHECK(a.fixes[k].original == b.fixes[k].original);
    CHECK(a.fixes[k].safety == b.fixes[k].safety);
  }
}

}  // namespace

TEST_CASE("compact findings: every field comes back, in order, across many text blocks") {
  tools::CompactFindings store;
  // ~30,000 findings of up to ~310 bytes fill several 1 MiB blocks.
  const int n = 30'000;
  for (int i = 0; i < n; ++i) store.report(finding(i));
  CHECK(store.size() == static_cast<std::size_t>(n));
  const std::vector<Diagnostic> back = store.take();
  REQUIRE(back.size() == static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) check_same(back[static_cast<std::size_t>(i)], finding(i));
  CHECK(store.size() == 0);
  CHECK(store.take().empty());
}

TEST_CASE("compact findings: a message larger than a block, and reuse after take") {
  tools::CompactFindings store;
  Diagnostic big = finding(1);
  big.message = std::string((1 << 20) + 5, 'm');
  store.report(finding(2));
  store.report(big);
  store.report(finding(3));
  std::vector<Diagnostic> back = store.take();
  REQUIRE(back.size() == 3);
  check_same(back[0], finding(2));
  check_same(back[1], big);
  check_same(back[2], finding(3));
  store.report(finding(26));  // equal hint after the store was emptied
  store.report(finding(39));
  back = store.take();
  REQUIRE(back.size() == 2);
  check_same(back[0], finding(26));
  check_same(back[1], finding(39));
}

TEST_CASE("compact findings: messages sharing any prefix and suffix with the rule's previous one") {
  // Short strings over two letters overlap in every way (prefix and suffix meeting, one
  // message inside the other, empty ones), across two interleaved rules.
  tools::CompactFindings store;
  std::vector<Diagnostic> sent;
  std::uint32_t seed = 12345;
  for (int i = 0; i < 5000; ++i) {
    seed = seed * 1664525u + 1013904223u;
    Diagnostic d = finding(i);
    d.rule_id = (seed >> 30) & 1 ? "rule-a" : "rule-b";
    d.message.clear();
    for (std::uint32_t k = 0, n = (seed >> 8) % 7; k < n; ++k) d.message.push_back((seed >> (k + 12)) & 1 ? 'a' : 'b');
    store.report(d);
    sent.push_back(d);
  }
  const std::vector<Diagnostic> back = store.take();
  REQUIRE(back.size() == sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) check_same(back[i], sent[i]);
}
