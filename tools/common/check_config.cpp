// `.bodycheck.yaml`: the per-tree policy settings of every tool (README "Configuration").
//
//   disable: [inertia-com-outside, units-*]   # rule ids or family prefixes
//   enable: [units-degree-looks-radian]       # wins over disable
//   fail_on: warning                          # or error
//   werror: true
//
// Read with the project's own YAML parser (yaml/yaml_node.h), so that the config and the body
// files share one YAML dialect and positions are 1-based like every other diagnostic.

#include "check_config.h"

#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/rules.h>

// The library's private YAML layer and text utilities: the config is the tools' concern, but
// it is read with the same YAML dialect and positions as the body files.
#include "text/text_util.h"
#include "yaml/yaml_node.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace bodyfmt::tools {
namespace {

void error(DiagnosticSink& sink, SourceLocation location, std::string message, std::string hint = {}) {
  report_rule(sink, "config-invalid", std::move(location), std::move(message), std::move(hint));
}

/// A scalar or a sequence of scalars, each a rule id or pattern the rule table knows.
bool read_rules(const yaml::NodeRef& node, const std::string& key, DiagnosticSink& sink,
                std::vector<std::string>& out) {
  std::vector<yaml::NodeRef> items;
  if (node->is_null()) return true;
  if (node->is_scalar()) {
    items.push_back(node);
  } else if (node->is_sequence()) {
    items.assign(node->items().begin(), node->items().end());
  } else {
    error(sink, node.use_site(), "'" + key + "' must be a list of rule ids");
    return false;
  }
  bool ok = true;
  for (const yaml::NodeRef& item : items) {
    if (!item->is_scalar()) {
      error(sink, item.use_site(), "'" + key + "' must be a list of rule ids");
      ok = false;
      continue;
    }
    const std::string id(item->scalar());
    std::string problem = check_rule_pattern(id);
    if (!problem.empty()) {
      error(sink, item.use_site(), problem);
      ok = false;
      continue;
    }
    out.push_back(id);
  }
  return ok;
}

}  // namespace

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
  auto document = yaml::parse_yaml(text, path, yaml::ParseOptions{}, yaml_sink);
  bool yaml_ok = document != nullptr;
  for (Diagnostic& d : yaml_sink.diagnostics()) {
    if (d.severity == Severity::kWarning || d.severity == Severity::kNote) {
      sink.report(std::move(d));  // e.g. a duplicated key: the config is still usable
    } else {
      error(sink, d.location, "malformed YAML: " + d.message);
      yaml_ok = false;
    }
  }
  if (!yaml_ok) return std::nullopt;

  CheckConfig config;
  config.path = path;
  const yaml::NodeRef& root = document->root;
  if (root->is_null()) return config;  // an empty file is a valid, empty config
  if (!root->is_mapping()) {
    error(sink, root.use_site(), "a .bodycheck.yaml must be a mapping", "keys: disable, enable, fail_on, werror");
    return std::nullopt;
  }
  bool ok = true;
  for (const yaml::MapEntry& entry : root->entries()) {
    const std::string key(entry.key);
    const yaml::NodeRef& value = entry.value;
    if (key == "disable" || key == "enable") {
      ok &= read_rules(value, key, sink, key == "disable" ? config.disable : config.enable);
    } else if (key == "fail_on") {
      const std::string v = value->is_scalar() ? std::string(value->scalar()) : std::string();
      if (v == "error") {
        config.fail_on = Severity::kError;
      } else if (v == "warning") {
        config.fail_on = Severity::kWarning;
      } else {
        error(sink, value.use_site(), "'fail_on' must be 'error' or 'warning'");
        ok = false;
      }
    } else if (key == "werror") {
      if (std::optional<bool> b = value->is_scalar() ? text::parse_bool_word(value->scalar()) : std::nullopt) {
        config.werror = *b;
      } else {
        error(sink, value.use_site(), "'werror' must be true or false");
        ok = false;
      }
    } else {
      error(sink, entry.key_location, "unknown key '" + key + "' in .bodycheck.yaml",
            "keys: disable, enable, fail_on, werror");
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  return config;
}

std::optional<CheckConfig> read_config(const std::string& path, DiagnosticSink& sink) {
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) {
    report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "cannot read the configuration file");
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return read_config_string(text.str(), path, sink);
}

}  // namespace bodyfmt::tools
