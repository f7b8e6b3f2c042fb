// `.bodycheck.yaml`: the per-tree policy settings of every tool (docs/tools/bodycheck.md, the paragraphs before
// "bodycheck in pre-commit").
//
//   disable: [inertia-com-outside, units-*]   # rule ids or family prefixes
//   enable: [units-degree-looks-radian]       # wins over disable
//   fail_on: warning                          # or error
//   werror: true
//   severity: {joint-id-on-fixed: error, inertia-*: note}   # raise or lower a rule
//
// Read with libbodyfmt's YAML API (bodyfmt/yaml.h), so that the config and the body files share
// one YAML dialect, one bounded file reader and 1-based positions like every other diagnostic.

#include "check_config.h"

#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/yaml.h>

#include <filesystem>

namespace bodyfmt::tools {
namespace {

constexpr const char* kRule = "config-invalid";

/// A scalar or a sequence of scalars, each a rule id or pattern the rule table knows.
bool read_rules(YamlReader& r, const YamlNode& node, const std::string& key, std::vector<std::string>& out) {
  std::vector<YamlNode> items;
  if (node.is_null()) return true;
  if (node.is_scalar()) {
    items.push_back(node);
  } else if (node.is_sequence()) {
    items = node.items();
  } else {
    r.error(node, "'" + key + "' must be a list of rule ids");
    return false;
  }
  bool ok = true;
  for (const YamlNode& item : items) {
    if (!item.is_scalar()) {
      r.error(item, "'" + key + "' must be a list of rule ids");
      ok = false;
      continue;
    }
    const std::string id(item.scalar());
    std::string problem = check_rule_pattern(id);
    if (!problem.empty()) {
      r.error(item, problem);
      ok = false;
      continue;
    }
    out.push_back(id);
  }
  return ok;
}

/// `severity: {RULE: LEVEL, ...}`.
void read_severities(YamlReader& r, const YamlNode& node, std::vector<std::pair<std::string, Severity>>& out) {
  if (node.is_null()) return;
  if (!node.is_mapping()) {
    r.error(node, "'severity' must be a mapping of rule ids to note, warning or error",
            "e.g. severity: {joint-id-on-fixed: error}");
    return;
  }
  for (const YamlEntry& entry : node.entries()) {
    const std::string id(entry.key);
    const std::string problem = check_rule_pattern(id);
    if (!problem.empty()) {
      r.error(entry.key_location, problem);
      continue;
    }
    const std::optional<Severity> level =
        entry.value.is_scalar() ? parse_rule_severity(entry.value.scalar()) : std::nullopt;
    if (!level) {
      r.error(entry.value, "the severity of '" + id + "' must be note, warning or error");
      continue;
    }
    out.emplace_back(id, *level);
  }
}

std::optional<CheckConfig> read_document(std::optional<YamlDocument> document, CollectingSink& yaml_sink,
                                         const std::string& path, DiagnosticSink& sink) {
  YamlReader r(sink, kRule);
  bool yaml_ok = document.has_value();
  for (Diagnostic& d : yaml_sink.diagnostics()) {
    if (d.severity == Severity::kWarning || d.severity == Severity::kNote || d.rule_id == "io-read") {
      sink.report(std::move(d));  // e.g. a duplicated key: the config is still usable
    } else {
      r.error(d.location, "malformed YAML: " + d.message);
    }
  }
  if (!yaml_ok || !r.ok()) return std::nullopt;

  CheckConfig config;
  config.path = path;
  const YamlNode root = document->root();
  if (root.is_null()) return config;  // an empty file is a valid, empty config
  if (!root.is_mapping()) {
    r.error(root, "a .bodycheck.yaml must be a mapping", "keys: disable, enable, fail_on, werror, severity");
    return std::nullopt;
  }
  r.known_keys(root, {"disable", "enable", "fail_on", "werror", "severity"}, ".bodycheck.yaml");
  for (const YamlEntry& entry : root.entries()) {
    const std::string key(entry.key);
    const YamlNode& value = entry.value;
    if (key == "disable" || key == "enable") {
      read_rules(r, value, key, key == "disable" ? config.disable : config.enable);
    } else if (key == "fail_on") {
      const std::string v = value.is_scalar() ? std::string(value.scalar()) : std::string();
      if (v == "error") {
        config.fail_on = Severity::kError;
      } else if (v == "warning") {
        config.fail_on = Severity::kWarning;
      } else {
        r.error(value, "'fail_on' must be 'error' or 'warning'");
      }
    } else if (key == "severity") {
      read_severities(r, value, config.severity);
    } else if (key == "werror") {
      if (std::optional<bool> b = r.boolean(value, "'werror'")) config.werror = *b;
    }
  }
  if (!r.ok()) return std::nullopt;
  return config;
}

}  // namespace

std::optional<Severity> parse_rule_severity(std::string_view level) {
  if (level == "note") return Severity::kNote;
  if (level == "warning") return Severity::kWarning;
  if (level == "error") return Severity::kError;
  return std::nullopt;
}

std::string find_config(const std::string& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path dir = fs::absolute(fs::path(file), ec).parent_path();
  if (ec) return {};
  for (;;) {
    fs::path candidate = dir / ".bodycheck.yaml";
    if (fs::is_regular_file(candidate, ec)) {
      // Relative to the working directory when below it, as the user would write it.
      fs::path normal = candidate.lexically_normal();
      fs::path relative = normal.lexically_relative(fs::current_path(ec));
      if (!ec && !relative.empty() && relative.begin()->string() != "..") return relative.string();
      return normal.string();
    }
    fs::path parent = dir.parent_path();
    if (parent == dir || parent.empty()) return {};
    dir = parent;
  }
}

std::optional<CheckConfig> read_config_string(const std::string& text, const std::string& path, DiagnosticSink& sink) {
  CollectingSink yaml_sink;
  std::optional<YamlDocument> document = parse_yaml_text(text, path, yaml_sink);
  return read_document(std::move(document), yaml_sink, path, sink);
}

std::optional<CheckConfig> read_config(const std::string& path, DiagnosticSink& sink) {
  CollectingSink yaml_sink;
  std::optional<YamlDocument> document = read_yaml_file(path, yaml_sink, YamlLimits{}, "the configuration file");
  return read_document(std::move(document), yaml_sink, path, sink);
}

}  // namespace bodyfmt::tools
