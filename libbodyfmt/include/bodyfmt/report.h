#pragma once
/// Writers for a list of diagnostics: GCC/Clang text with source lines and carets, JSON
/// (docs/bodycheck-json.md) and SARIF 2.1.0. All three take the same Report, whose
/// diagnostics are sorted by file, line, column and rule (sort_diagnostics), so the output
/// is deterministic. The writers never throw on odd input and never print.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>

#include <iosfwd>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// What a run checked and found.
struct Report {
  std::vector<std::string> files;       ///< every file checked, in output order
  std::vector<Diagnostic> diagnostics;  ///< in output order (see sort_diagnostics)
  int suppressed = 0;                   ///< dropped by inline suppressions
  int disabled = 0;                     ///< dropped because their rule is disabled

  int count(Severity severity) const;
  /// Diagnostics per rule id.
  std::map<std::string, int> counts_by_rule() const;
};

/// The lines of source files, each file read once, for carets and suppressions.
class SourceLines {
 public:
  /// Only the files given by add() and add_file() are quoted: a finding located in any other
  /// file (one a hostile model names, which may be a credentials file) prints no source line.
  SourceLines() = default;
  /// Lines of any readable file, for what only measures a line and never prints it (SARIF's
  /// code-point columns).
  static SourceLines any_file_for_columns();

  /// Uses `text` as the contents of `file` (text that is not on disk: standard input).
  void add(const std::string& file, std::string_view text);
  /// `file` was read as model text (LoadOptions::on_model_text): its lines may be quoted,
  /// read from disk when first asked for. A file given to add() keeps that text.
  void add_file(const std::string& file);
  /// Line `line` (1-based) of `file` without its line break, or nullopt when the file was not
  /// added, cannot be read or is shorter.
  std::optional<std::string_view> line(const std::string& file, int line);

 private:
  struct Text {
    std::string text;
    std::vector<std::string_view> lines;  ///< into `text`
  };
  /// Node-based: a Text never moves, so its line views stay valid. A file added by name and
  /// not yet read is absent here and listed in `model_files_`.
  std::map<std::string, std::optional<Text>> files_;
  std::set<std::string> model_files_;
  bool any_file_ = false;
};

struct TextOptions {
  bool source_lines = true;  ///< print the source line and a caret under the column
  bool notes = true;         ///< print note-severity diagnostics and the note lines attached to others
  bool color = false;        ///< ANSI colours as GCC and Clang use them (bold location, coloured severity, green caret)
};

/// One diagnostic in GCC/Clang style:
///
///     file:line:col: severity: message [rule-id]
///       <the source line>
///           ^
///     file:line:col: note: reached through this alias      (when `via` is set)
///     file:line:col: note: <fix hint>                      (when there is one)
///
/// The caret line copies the tabs of the source line so that it lines up; the column counts
/// bytes and the caret advances one per UTF-8 character. Ends with a newline.
std::string format_text_diagnostic(const Diagnostic& diagnostic, SourceLines& sources, const TextOptions& options = {});

/// Every diagnostic of the report, in order.
std::string format_text_report(const Report& report, SourceLines& sources, const TextOptions& options = {});
/// The same text written to `out` a block at a time, so that a report of a million findings
/// is never held as one string.
void write_text_report(std::ostream& out, const Report& report, SourceLines& sources, const TextOptions& options = {});

/// `bodycheck: N files checked: E errors, W warnings, K notes` (+ suppressed/disabled counts).
std::string format_summary_line(const Report& report);

struct ToolInfo {
  std::string name = "bodycheck";
  std::string version;          ///< required by SARIF consumers; the project version
  std::string information_uri;  ///< absolute URI of the tool's documentation
};

/// The JSON document of docs/bodycheck-json.md (schema version 1), with a final newline.
std::string format_json_report(const Report& report, const ToolInfo& tool);

/// A SARIF 2.1.0 log with one run. Locations are relative to `base_dir` (the working
/// directory when empty) when the file lies under it, with forward slashes and
/// `uriBaseId` "%SRCROOT%" (declared in originalUriBaseIds); other files get absolute
/// `file://` URIs. Rules come from the rule table. With a final newline.
std::string format_sarif_report(const Report& report, const ToolInfo& tool, const std::string& base_dir = {});

}  // namespace bodyfmt
#pragma GCC visibility pop
