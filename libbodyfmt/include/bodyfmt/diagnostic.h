#pragma once
/// Diagnostics: one value type and one sink interface shared by every stage.
///
/// Stages never throw on bad input and never print; they report a Diagnostic to the
/// DiagnosticSink they were given and carry on with a safe value where that still means
/// something (SDFormat's error list, Drake's diagnostic policy).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt {

enum class Severity { kNote, kWarning, kError, kFatal };

std::string_view severity_name(Severity severity);

/// A position in a source file. Line and column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  bool known() const { return line > 0; }
  friend bool operator==(const SourceLocation& a, const SourceLocation& b) {
    return a.file == b.file && a.line == b.line && a.column == b.column;
  }
  friend bool operator!=(const SourceLocation& a, const SourceLocation& b) { return !(a == b); }
};

struct Diagnostic {
  Severity severity = Severity::kError;
  std::string rule_id;  ///< stable kebab-case id from the rule table, e.g. "yaml-duplicate-key"
  std::string message;
  SourceLocation location;
  std::optional<SourceLocation> via;  ///< alias use site when the value came through *anchor
  std::string fix_hint;
};

/// Receives diagnostics. Implementations must not throw.
class DiagnosticSink {
 public:
  virtual ~DiagnosticSink() = default;
  virtual void report(Diagnostic diagnostic) = 0;
};

/// Keeps every diagnostic in arrival order and counts them by severity.
class CollectingSink : public DiagnosticSink {
 public:
  void report(Diagnostic diagnostic) override;
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  std::vector<Diagnostic>& diagnostics() { return diagnostics_; }
  int count(Severity severity) const;
  /// Errors and fatals.
  int error_count() const { return count(Severity::kError) + count(Severity::kFatal); }
  bool has(std::string_view rule_id) const;
  void clear() { diagnostics_.clear(); }

 private:
  std::vector<Diagnostic> diagnostics_;
};

/// Forwards to another sink, tagging every diagnostic that has no location with a default one.
/// Useful where location-blind code runs on behalf of a located element.
class LocatingSink : public DiagnosticSink {
 public:
  LocatingSink(DiagnosticSink& inner, SourceLocation fallback) : inner_(inner), fallback_(std::move(fallback)) {}
  void report(Diagnostic diagnostic) override;

 private:
  DiagnosticSink& inner_;
  SourceLocation fallback_;
};

/// `file:line:col: severity: message [rule-id]`, then `note:` lines for `via` and the hint.
std::string format_diagnostic(const Diagnostic& diagnostic);

/// Sorts by file, line, column and rule id so that output is deterministic.
void sort_diagnostics(std::vector<Diagnostic>& diagnostics);

}  // namespace bodyfmt
