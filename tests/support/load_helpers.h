#pragma once
/// Helpers for loader unit tests, in the spirit of Drake's DiagnosticPolicyTestBase: load a
/// text, then take() the diagnostics a test expects one by one (checking rule id, line and
/// column, never wording) and finish with expect_clean(), which fails on any warning or error
/// nobody took.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/load.h>
#include <bodyfmt/model.h>

#include <doctest/doctest.h>

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::test {

/// A 1-based line/column pair, printable in doctest failure messages.
struct Pos {
  int line = 0;
  int column = 0;
  friend bool operator==(const Pos& a, const Pos& b) { return a.line == b.line && a.column == b.column; }
  friend std::ostream& operator<<(std::ostream& os, const Pos& p) { return os << p.line << ":" << p.column; }
};

inline Pos pos(const SourceLocation& location) { return {location.line, location.column}; }
inline Pos pos(const Diagnostic& d) { return pos(d.location); }

struct LoadResult {
  std::optional<Model> model;
  std::vector<Diagnostic> diagnostics;

  /// The loaded model; fails the test (REQUIRE) when loading returned nothing.
  const Model& m() const;
  /// Removes and returns the first diagnostic with this rule id. When there is none the check
  /// fails and a diagnostic with rule id "<missing>" at 0:0 is returned.
  Diagnostic take(std::string_view rule_id);
  /// Whether a diagnostic with this rule id remains (without removing it).
  bool has(std::string_view rule_id) const;
  int count(std::string_view rule_id) const;
  /// Fails for every remaining warning, error or fatal (notes are informational and allowed).
  void expect_clean() const;
  /// Drops every remaining note with this rule id (e.g. "load-info-key").
  void drop_notes(std::string_view rule_id);
  /// The link with this name; fails the test (REQUIRE) when absent.
  const Link& link(std::string_view name) const;
};

/// Loads `text` as "test.body". One leading newline is removed, so that a raw string literal
/// starting with a line break has the line after `R"(` as line 1.
LoadResult load(std::string_view text, const std::string& file_name = "test.body");

/// Prepends a two-line header (`format: ChoreonoidBody`, `format_version: 2.0`), so line 3 of
/// the loaded text is the first line of `rest` (after the leading newline is removed).
LoadResult load_v2(std::string_view rest);

std::string describe(const std::vector<Diagnostic>& diagnostics);

}  // namespace bodyfmt::test
