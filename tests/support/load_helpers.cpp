#include "support/load_helpers.h"

#include <algorithm>

namespace bodyfmt::test {

std::string describe(const std::vector<Diagnostic>& diagnostics) {
  std::string out;
  for (const Diagnostic& d : diagnostics) out += format_diagnostic(d) + "\n";
  return out.empty() ? std::string("(none)") : out;
}

const Model& LoadResult::m() const {
  INFO("diagnostics:\n" << describe(diagnostics));
  REQUIRE(model.has_value());
  return *model;
}

Diagnostic LoadResult::take(std::string_view rule_id) {
  auto it =
      std::find_if(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& d) { return d.rule_id == rule_id; });
  if (it == diagnostics.end()) {
    FAIL_CHECK("expected a diagnostic [" << rule_id << "]; got:\n" << describe(diagnostics));
    Diagnostic missing;
    missing.rule_id = "<missing>";
    return missing;
  }
  Diagnostic d = *it;
  diagnostics.erase(it);
  return d;
}

bool LoadResult::has(std::string_view rule_id) const { return count(rule_id) > 0; }

int LoadResult::count(std::string_view rule_id) const {
  return static_cast<int>(
      std::count_if(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& d) { return d.rule_id == rule_id; }));
}

void LoadResult::expect_clean() const {
  for (const Diagnostic& d : diagnostics) {
    if (d.severity == Severity::kNote) continue;
    FAIL_CHECK("unexpected diagnostic: " << format_diagnostic(d));
  }
}

void LoadResult::drop_notes(std::string_view rule_id) {
  diagnostics.erase(
      std::remove_if(diagnostics.begin(), diagnostics.end(),
                     [&](const Diagnostic& d) { return d.severity == Severity::kNote && d.rule_id == rule_id; }),
      diagnostics.end());
}

const Link& LoadResult::link(std::string_view name) const {
  const Model& model_ref = m();
  LinkIndex i = model_ref.find_link(name);
  INFO("link " << std::string(name));
  REQUIRE(i >= 0);
  return model_ref.links[static_cast<std::size_t>(i)];
}

LoadResult load(std::string_view text, const std::string& file_name) {
  if (!text.empty() && text.front() == '\n') text.remove_prefix(1);
  CollectingSink sink;
  LoadResult result;
  result.model = load_body_string(std::string(text), file_name, LoadOptions{}, sink);
  result.diagnostics = sink.diagnostics();
  return result;
}

LoadResult load_v2(std::string_view rest) {
  if (!rest.empty() && rest.front() == '\n') rest.remove_prefix(1);
  std::string text = "format: ChoreonoidBody\nformat_version: 2.0\n";
  text.append(rest);
  return load(text);
}

}  // namespace bodyfmt::test
