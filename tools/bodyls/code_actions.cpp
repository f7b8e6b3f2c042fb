#include "code_actions.h"

#include "lsp_convert.h"
#include "mass_action.h"

#include <algorithm>
#include <map>

namespace bodyfmt::lsp {

using json = nlohmann::json;

namespace {

bool before(Utf16Position a, Utf16Position b) {
  return a.line < b.line || (a.line == b.line && a.character < b.character);
}

/// Touching counts: a cursor just after a token is on it.
bool overlaps(Utf16Range a, Utf16Range b) { return !before(a.end, b.start) && !before(b.end, a.start); }

/// True when an action of `kind` is wanted under `only` (a kind matches itself and its
/// sub-kinds, as the protocol says).
bool wanted(const std::vector<std::string>& only, const std::string& kind) {
  if (only.empty()) return true;
  return std::any_of(only.begin(), only.end(), [&](const std::string& k) {
    return kind == k || (kind.size() > k.size() && kind.compare(0, k.size(), k) == 0 && kind[k.size()] == '.');
  });
}

/// The upgrade is asked for by name: its kind or "quickfix.bodyfmt", never by "quickfix" alone.
bool upgrade_asked(const std::vector<std::string>& only) {
  return std::any_of(only.begin(), only.end(),
                     [](const std::string& k) { return k == kUpgradeActionKind || k == "quickfix.bodyfmt"; });
}

std::string shorten(const std::string& s) {
  std::string out = s.size() > 40 ? s.substr(0, 37) + "..." : s;
  std::replace(out.begin(), out.end(), '\n', ' ');
  return out;
}

/// The workspace edit of `fixes`, or null when one of them no longer fits its file's text.
json workspace_edit(const std::vector<FixIt>& fixes, FileTexts& texts) {
  std::map<std::string, json> changes;
  std::vector<FixIt> seen;
  for (const FixIt& f : fixes) {
    if (std::find(seen.begin(), seen.end(), f) != seen.end()) continue;  // one edit shared by aliases
    seen.push_back(f);
    const std::string file = f.file.str();
    const std::string* text = texts.text(file);
    if (!text || f.end > text->size() || text->compare(f.begin, f.end - f.begin, f.original) != 0) return nullptr;
    const auto range = texts.byte_range(file, f.begin, f.end);
    if (!range) return nullptr;
    json& list = changes[texts.uri(file)];
    if (list.is_null()) list = json::array();
    list.push_back({{"range", to_json(*range)}, {"newText", f.replacement}});
  }
  json out = json::object();
  for (auto& [uri, list] : changes) out[uri] = std::move(list);
  return json{{"changes", out}};
}

}  // namespace

json code_actions_for(const std::string& uri, const std::string& path, const std::string& text,
                      const std::vector<Diagnostic>& findings, const CodeActionQuery& query) {
  static const std::map<std::string, std::string> no_other_texts;
  FileTexts texts(path, uri, text, no_other_texts);
  json actions = json::array();
  const bool quickfixes = wanted(query.only, "quickfix");
  const bool upgrade = upgrade_asked(query.only);
  // The upgrade converts every radian value to degrees, those that a finding calls degrees too,
  // and that finding then has nothing to judge: while one stands, the user decides first.
  const auto degree_finding = std::find_if(findings.begin(), findings.end(), [](const Diagnostic& d) {
    return d.rule_id == "units-range-looks-degree" || d.rule_id == "units-velocity-looks-degree";
  });
  for (const Diagnostic& d : findings) {
    if (d.fixes.empty() || texts.uri(d.location.file.str()) != uri) continue;
    if (!overlaps(texts.token_range(d.location.file.str(), d.location.line, d.location.column), query.range)) continue;
    const json diagnostic = diagnostic_to_json(d, texts);
    std::vector<FixIt> upgrade_fixes;
    for (const FixIt& f : d.fixes) {
      const std::string what = f.original.empty() ? "insert \"" + shorten(f.replacement) + "\""
                               : f.replacement.empty()
                                   ? "delete \"" + shorten(f.original) + "\""
                                   : "\"" + shorten(f.original) + "\" -> \"" + shorten(f.replacement) + "\"";
      if (f.safety == FixSafety::kUpgrade) {
        upgrade_fixes.push_back(f);
      } else if (f.safety == FixSafety::kSafe && quickfixes) {
        json edit = workspace_edit({f}, texts);
        if (edit.is_null()) continue;
        actions.push_back({{"title", "Fix " + d.rule_id + ": " + what},
                           {"kind", "quickfix"},
                           {"diagnostics", json::array({diagnostic})},
                           {"isPreferred", true},
                           {"edit", std::move(edit)}});
      } else if (f.safety == FixSafety::kUnsafe && quickfixes) {
        // An edit that changes the model Choreonoid loads (a did-you-mean key, a parent's
        // name): choosing it from the menu is the user's consent, so it is offered with its
        // edit, but never as the preferred fix (clients apply those without asking, e.g. on
        // save) and under "quickfix" only, never in a bulk kind such as source.fixAll.
        json edit = workspace_edit({f}, texts);
        if (edit.is_null()) continue;
        actions.push_back({{"title", "Fix " + d.rule_id + ": " + what + " (changes the model)"},
                           {"kind", "quickfix"},
                           {"diagnostics", json::array({diagnostic})},
                           {"edit", std::move(edit)}});
      }
    }
    if (!upgrade_fixes.empty() && upgrade && degree_finding != findings.end()) {
      if (query.disabled_support)
        actions.push_back(
            {{"title", "Upgrade to format 2.0"},
             {"kind", kUpgradeActionKind},
             {"diagnostics", json::array({diagnostic})},
             {"disabled",
              {{"reason", "line " + std::to_string(degree_finding->location.line) + " looks like degrees [" +
                              degree_finding->rule_id +
                              "]: the upgrade would convert it as radians; reinterpret it (its quick fix) or "
                              "suppress the finding first"}}}});
    } else if (!upgrade_fixes.empty() && upgrade) {
      json edit = workspace_edit(upgrade_fixes, texts);
      if (edit.is_null()) continue;
      actions.push_back({{"title", "Upgrade to format 2.0 (" + std::to_string(upgrade_fixes.size()) +
                                       (upgrade_fixes.size() == 1 ? " edit)" : " edits)")},
                         {"kind", kUpgradeActionKind},
                         {"diagnostics", json::array({diagnostic})},
                         {"edit", std::move(edit)}});
    }
  }
  // The shapes are integrated only when one of the action's two kinds is wanted.
  if (query.model && (quickfixes || wanted(query.only, kMassFromShapesKind))) {
    const std::optional<MassFromShapes> mass =
        mass_from_shapes(*query.model, path, text, findings, query.range.start.line + 1);
    const char* kind = mass && mass->flagged ? "quickfix" : kMassFromShapesKind;
    if (mass && wanted(query.only, kind)) {
      json edit = mass->fixes.empty() ? json() : workspace_edit(mass->fixes, texts);
      if (!edit.is_null())
        actions.push_back({{"title", mass->title}, {"kind", kind}, {"edit", std::move(edit)}});
      else if (query.disabled_support)
        actions.push_back({{"title", mass->title}, {"kind", kind}, {"disabled", {{"reason", mass->unavailable}}}});
    }
  }
  return actions;
}

}  // namespace bodyfmt::lsp
