// `.bodycheck.yaml`: the per-tree configuration of bodycheck (README "Configuration").
//
//   disable: [inertia-com-outside, units-*]   # rule ids or family prefixes
//   enable: [units-degree-looks-radian]       # wins over disable
//   fail_on: warning                          # or error
//   werror: true
//
// yaml-cpp is private to libbodyfmt; its marks are 0-based, so 1 is added here.

#include <bodyfmt/diagnostic_policy.h>

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

namespace bodyfmt {
namespace {

SourceLocation at(const std::string& path, const YAML::Mark& mark) {
  SourceLocation loc;
  loc.file = path;
  if (mark.line >= 0) {
    loc.line = mark.line + 1;
    loc.column = mark.column + 1;
  }
  return loc;
}

void error(DiagnosticSink& sink, const std::string& path, const YAML::Mark& mark, std::string message,
           std::string hint = {}) {
  Diagnostic d;
  d.severity = Severity::kError;
  d.rule_id = "config-invalid";
  d.message = std::move(message);
  d.location = at(path, mark);
  d.fix_hint = std::move(hint);
  sink.report(std::move(d));
}

/// A scalar or a sequence of scalars, each a rule id or pattern the rule table knows.
bool read_rules(const YAML::Node& node, const std::string& key, const std::string& path,
                DiagnosticSink& sink, std::vector<std::string>& out) {
  std::vector<YAML::Node> items;
  if (node.IsNull()) return true;
  if (node.IsScalar()) items.push_back(node);
  else if (node.IsSequence())
    for (const auto& item : node) items.push_back(item);
  else {
    error(sink, path, node.Mark(), "'" + key + "' must be a list of rule ids");
    return false;
  }
  bool ok = true;
  for (const YAML::Node& item : items) {
    if (!item.IsScalar()) {
      error(sink, path, item.Mark(), "'" + key + "' must be a list of rule ids");
      ok = false;
      continue;
    }
    const std::string id = item.Scalar();
    std::string problem = check_rule_pattern(id);
    if (!problem.empty()) {
      error(sink, path, item.Mark(), problem);
      ok = false;
      continue;
    }
    out.push_back(id);
  }
  return ok;
}

}  // namespace

std::optional<CheckConfig> read_config_string(const std::string& text, const std::string& path,
                                              DiagnosticSink& sink) {
  try {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      error(sink, path, e.mark, "malformed YAML: " + e.msg);
      return std::nullopt;
    }
    CheckConfig config;
    config.path = path;
    if (root.IsNull()) return config;  // an empty file is a valid, empty config
    if (!root.IsMap()) {
      error(sink, path, root.Mark(), "a .bodycheck.yaml must be a mapping",
            "keys: disable, enable, fail_on, werror");
      return std::nullopt;
    }
    bool ok = true;
    for (const auto& entry : root) {
      const YAML::Node& key_node = entry.first;
      const YAML::Node& value = entry.second;
      const std::string key = key_node.IsScalar() ? key_node.Scalar() : std::string();
      if (key == "disable" || key == "enable") {
        ok &= read_rules(value, key, path, sink, key == "disable" ? config.disable : config.enable);
      } else if (key == "fail_on") {
        const std::string v = value.IsScalar() ? value.Scalar() : std::string();
        if (v == "error") config.fail_on = Severity::kError;
        else if (v == "warning") config.fail_on = Severity::kWarning;
        else {
          error(sink, path, value.Mark(), "'fail_on' must be 'error' or 'warning'");
          ok = false;
        }
      } else if (key == "werror") {
        bool b = false;
        if (value.IsScalar() && YAML::convert<bool>::decode(value, b)) config.werror = b;
        else {
          error(sink, path, value.Mark(), "'werror' must be true or false");
          ok = false;
        }
      } else {
        error(sink, path, key_node.Mark(), "unknown key '" + key + "' in .bodycheck.yaml",
              "keys: disable, enable, fail_on, werror");
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    return config;
  } catch (const std::exception& e) {
    error(sink, path, YAML::Mark::null_mark(), std::string("cannot read the config: ") + e.what());
    return std::nullopt;
  }
}

std::optional<CheckConfig> read_config(const std::string& path, DiagnosticSink& sink) {
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) {
    Diagnostic d;
    d.severity = Severity::kError;
    d.rule_id = "io-read";
    d.message = "cannot read the configuration file";
    d.location.file = path;
    sink.report(std::move(d));
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return read_config_string(text.str(), path, sink);
}

}  // namespace bodyfmt
