#pragma once
// State shared by the readers of one body file: where diagnostics go, the angle unit, and
// helpers that turn YAML nodes into located diagnostics.

#include <bodyfmt/diagnostic.h>

#include "yaml/yaml_node.h"

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace bodyfmt::detail {

struct LoadContext {
  DiagnosticSink& sink;
  bool degrees = true;  ///< the file's angle unit (body-format-spec §3)
  int errors = 0;
  /// Roots searched for `package://NAME/...` before ROS_PACKAGE_PATH.
  std::vector<std::string> package_paths;
  /// Keys of diagnostics that are reported once per load (e.g. one per plugin node type).
  std::set<std::string> reported_once;
  /// (rule, file, line, column, message) of every diagnostic so far: text shared through
  /// aliases is read once per use, but a problem in it is reported once.
  std::set<std::tuple<std::string, std::string, int, int, std::string>> reported;

  explicit LoadContext(DiagnosticSink& s) : sink(s) {}

  /// Reports `rule` with the rule table's severity at the text responsible.
  void report(std::string_view rule, const yaml::NodeRef& at, std::string message, std::string hint = {});
  void report(std::string_view rule, const SourceLocation& at, std::string message, std::string hint = {});

  /// Converts an angle written in the file's unit to radians.
  double angle(double value) const;

 private:
  void emit(std::string_view rule, const SourceLocation& at, std::optional<SourceLocation> via, std::string message,
            std::string hint);
};

}  // namespace bodyfmt::detail
