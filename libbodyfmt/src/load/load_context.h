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

/// A fix-it that replaces the text of scalar `node` (nullopt when it is not written verbatim).
std::optional<FixIt> edit_value(const yaml::Node& node, std::string replacement, FixSafety safety);
/// A fix-it that renames the key of `entry` (nullopt when it is not written verbatim).
std::optional<FixIt> edit_key(const yaml::MapEntry& entry, std::string replacement, FixSafety safety);
/// Shortest text that reads back as `value` (fmt's "{}"), for rewritten numbers.
std::string number_text(double value);
/// `radians` in degrees for the format upgrade: the shortest text that the loader reads back as
/// the same radians, bit for bit.
std::string degrees_text(double radians);

struct LoadContext;

/// The lines a block mapping entry is written on: from the start of its key's line to the end
/// of the last line below it indented deeper than the key (its value); blank and comment lines
/// after the value are not part of it. `indent` is the key's column - 1.
struct EntryLines {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t indent = 0;
};
/// nullopt when the key does not start its line (a flow mapping, the first key of `- key:`),
/// when the entry was merged in or `mapping` reached through an alias (other uses share the
/// text), or when the text of the entry's file is not at hand (LoadContext::text).
std::optional<EntryLines> entry_lines(const LoadContext& ctx, const yaml::NodeRef& mapping,
                                      const yaml::MapEntry& entry);

struct LoadContext {
  DiagnosticSink& sink;
  bool degrees = true;  ///< the file's angle unit (body-format-spec §3)
  /// While a file with its own angle unit is read (a .scen scene file): the body's format
  /// upgrade does not rewrite that file's angles, so none are recorded.
  bool own_angle_unit = false;
  /// Of a primitive without division_number: 20, or a wrapper's geometry.divisionNumber (§2.4).
  int default_division_number = 20;
  int errors = 0;
  /// Roots searched for `package://NAME/...` before ROS_PACKAGE_PATH, and whether that is.
  std::vector<std::string> package_paths;
  bool use_ros_package_path = true;
  /// Keys of diagnostics that are reported once per load (e.g. one per plugin node type).
  std::set<std::string> reported_once;
  /// (rule, file, line, column, message) of every diagnostic so far: text shared through
  /// aliases is read once per use, but a problem in it is reported once.
  std::set<std::tuple<std::string, std::string, int, int, std::string>> reported;

  /// The text of the body file being read (named `text_file`), while it is read: fix-its that
  /// move or delete an entry's lines need the bytes around it (entry_lines). Empty otherwise.
  std::string_view text;
  FileName text_file;

  explicit LoadContext(DiagnosticSink& s) : sink(s) {}

  /// Format-upgrade edits (load-format-upgrade): in a radian-mode file, every angle value the
  /// loader converts (body-format-spec §3), rewritten in degrees; each written text once.
  std::vector<FixIt> upgrade_fixes;
  /// (file, begin, end, replacement) of each upgrade fix: a lookup per angle instead of a
  /// scan of all the fixes so far (quadratic on a radian file of many links).
  std::set<std::tuple<const std::string*, std::size_t, std::size_t, std::string>> upgrade_fix_keys;
  /// Angle values that cannot be rewritten in place (block scalars, escapes): no upgrade.
  std::vector<SourceLocation> upgrade_blockers;

  /// Reports `rule` with the rule table's severity at the text responsible.
  void report(std::string_view rule, const yaml::NodeRef& at, std::string message, std::string hint = {},
              std::vector<FixIt> fixes = {});
  void report(std::string_view rule, const SourceLocation& at, std::string message, std::string hint = {},
              std::vector<FixIt> fixes = {});

  /// Converts the angle `value`, written at `at` in the file's unit, to radians. In a radian-mode
  /// file, also records the upgrade edit that writes it in degrees.
  double angle(double value, const yaml::NodeRef& at);
  /// An angle value Choreonoid converts but the model does not keep (a texture transform's
  /// rotation, a MarkerDevice offset_rotation...): only its upgrade edit is recorded.
  void note_angle(const yaml::NodeRef& at);
  /// The same for each angle (4th number) of an axis-angle rotation or a list of them.
  void note_rotation_angles(const yaml::NodeRef& rotation);

 private:
  void emit(std::string_view rule, const SourceLocation& at, std::optional<SourceLocation> via, std::string message,
            std::string hint, std::vector<FixIt> fixes);
  void record_upgrade(const yaml::NodeRef& at, double radians);
};

}  // namespace bodyfmt::detail
