#pragma once
/// DiagnosticPolicy: how strict a run is, applied in one place (style.md §2.3).
///
/// Stages report with the rule table's default severities and know nothing about the run.
/// A DiagnosticPolicy wraps the sink they report to and applies, in this order: per-rule
/// enable/disable, inline suppressions (`# bodycheck: disable=RULE`), per-rule severities,
/// `strict` (`export-loss` and `export-value-changed` become errors) and `werror` (warnings become errors). It
/// counts what it forwards by severity and by rule. It never throws. Fatal diagnostics are never dropped or changed.
///
/// The `.bodycheck.yaml` file that sets these options for a folder is the tools' business
/// (tools/common/check_config.h).

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>

#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// Per-rule switches. A rule pattern is a rule id or a family prefix ending in `*`
/// (`units-*`). A rule is off when a disable pattern matches it and no enable pattern does:
/// `enable` wins, so a command-line `--enable` can switch back on what a config turned off.
struct PolicyOptions {
  std::vector<std::string> disable;
  std::vector<std::string> enable;
  /// Per-rule severities, (rule pattern, note/warning/error), applied before `werror`; a later
  /// entry matching the same rule wins (a config's first, then the command line's).
  std::vector<std::pair<std::string, Severity>> severities;
  bool werror = false;  ///< warnings become errors
  /// `export-loss` and `export-value-changed` findings become errors (converters): what a target
  /// cannot express and what a writer changes on the way out are refused alike.
  bool strict = false;
  bool inline_suppressions = true;
};

/// True when `pattern` (an id or `prefix*`) matches `rule_id`.
bool rule_pattern_matches(std::string_view pattern, std::string_view rule_id);

/// Checks a rule pattern against the rule table. Returns an empty string when it names a
/// rule (or, for `prefix*`, at least one rule); otherwise the message for the user, with a
/// did-you-mean suggestion when a rule id is close.
std::string check_rule_pattern(std::string_view pattern);

/// The `# bodycheck: disable=RULE[,RULE2]` comments of one file, by the line they cover.
/// A comment after YAML content covers its own line; a line holding only the comment covers
/// the next line that is not itself such a comment line (so several can be stacked).
class Suppressions {
 public:
  /// One rule id (or `prefix*`) of one comment, where it is written, and whether it has
  /// suppressed a finding yet.
  struct Directive {
    std::string id;
    int line = 0;
    int column = 0;
    bool used = false;
  };

  Suppressions() = default;
  static Suppressions from_text(std::string_view text);
  static Suppressions from_stream(std::istream& in);
  /// True when `rule_id` is suppressed on 1-based `line`; the directives that match are
  /// marked used.
  bool suppresses(int line, std::string_view rule_id);
  bool empty() const { return by_line_.empty(); }
  const std::vector<Directive>& directives() const { return directives_; }

 private:
  /// Reads line `line_number`; `pending` holds the directives of comment-only lines above it.
  void add_line(std::string_view line, int line_number, std::vector<std::size_t>& pending);

  std::vector<Directive> directives_;
  std::map<int, std::vector<std::size_t>> by_line_;  ///< covered line -> directives_ indices
};

/// A sink wrapping a sink; see the file comment. Suppression comments are read from the
/// file a diagnostic points at, once per file, the first time a diagnostic needs them (or
/// given with set_suppressions, e.g. for text that is not on disk).
class DiagnosticPolicy : public DiagnosticSink {
 public:
  explicit DiagnosticPolicy(DiagnosticSink& inner, PolicyOptions options = {});

  void report(Diagnostic diagnostic) override;

  /// Uses `suppressions` for `file` instead of reading it.
  void set_suppressions(const std::string& file, Suppressions suppressions);

  bool enabled(std::string_view rule_id) const;
  const PolicyOptions& options() const { return options_; }

  /// Counts of what was forwarded, after severity changes.
  int count(Severity severity) const { return counts_[static_cast<int>(severity)]; }
  int error_count() const { return count(Severity::kError) + count(Severity::kFatal); }
  /// Forwarded diagnostics per rule id.
  const std::map<std::string, int>& counts_by_rule() const { return by_rule_; }
  int disabled_count() const { return disabled_; }
  int suppressed_count() const { return suppressed_; }

  /// After every check of `file` has reported: `suppression-unknown-rule` for each id of its
  /// `# bodycheck: disable=` comments that names no rule (with a did-you-mean) and
  /// `suppression-unused` for each that suppressed nothing (enabled rules only).
  void report_suppression_problems(const std::string& file);

 private:
  Suppressions& suppressions_for(const std::string& file);

  DiagnosticSink& inner_;
  PolicyOptions options_;
  std::map<std::string, Suppressions> suppressions_;
  std::map<std::string, bool> enabled_cache_;
  std::map<std::string, std::optional<Severity>> severity_cache_;
  int counts_[4] = {0, 0, 0, 0};
  std::map<std::string, int> by_rule_;
  int disabled_ = 0;
  int suppressed_ = 0;
};

}  // namespace bodyfmt
#pragma GCC visibility pop
