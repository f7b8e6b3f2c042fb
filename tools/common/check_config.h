#pragma once
/// `.bodycheck.yaml`: the per-folder settings of every tool's diagnostic policy (README
/// "Configuration"). Read with the library's YAML layer, so that errors in it are located.

#include <bodyfmt/diagnostic.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bodyfmt::tools {

/// The contents of a `.bodycheck.yaml`. Absent keys stay empty.
struct CheckConfig {
  std::string path;  ///< the file it was read from
  std::vector<std::string> disable;
  std::vector<std::string> enable;
  std::optional<Severity> fail_on;  ///< kWarning or kError
  std::optional<bool> werror;
  /// `severity: {RULE: LEVEL}`: rule ids or patterns with note, warning or error, in file order.
  std::vector<std::pair<std::string, Severity>> severity;
};

/// note, warning or error (the severities a policy may give a rule); nullopt otherwise.
std::optional<Severity> parse_rule_severity(std::string_view level);

/// The nearest `.bodycheck.yaml`, walking up from the directory of `file` (made absolute
/// first). Empty when there is none up to the file system root.
std::string find_config(const std::string& file);

/// Reads a config file. Reports `config-invalid` errors at the offending line and column
/// (unknown keys, wrong types, unknown rule ids, YAML syntax) and `io-read` when the file
/// cannot be read; returns nullopt when anything was wrong.
std::optional<CheckConfig> read_config(const std::string& path, DiagnosticSink& sink);

/// Same, from text (`path` is used in locations).
std::optional<CheckConfig> read_config_string(const std::string& text, const std::string& path, DiagnosticSink& sink);

}  // namespace bodyfmt::tools
