#pragma once
/// Diagnostics: one value type and one sink interface shared by every stage.
///
/// Stages never throw on bad input and never print; they report a Diagnostic to the
/// DiagnosticSink they were given and carry on with a safe value where that still means
/// something (SDFormat's error list, Drake's diagnostic policy).

#include <bodyfmt/export.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

enum class Severity { kNote, kWarning, kError, kFatal };

std::string_view severity_name(Severity severity);

/// A file name as locations carry it: interned once per process, so that the millions of
/// locations of a large model share one copy, and a location is 12 bytes (the name is a 32-bit
/// number in the process's table of names). Reads as the std::string it names; equal names
/// are the same number.
class FileName {
 public:
  FileName() = default;
  FileName(const std::string& name);  // NOLINT: implicit, a location's file is set from strings
  FileName(const char* name) : FileName(std::string(name)) {}
  FileName(std::string_view name) : FileName(std::string(name)) {}

  const std::string& str() const;
  operator const std::string&() const { return str(); }  // NOLINT: reads as a string
  bool empty() const { return id_ == 0; }                // the empty name is never interned
  const char* c_str() const { return str().c_str(); }

  friend bool operator==(FileName a, FileName b) { return a.id_ == b.id_; }
  friend bool operator!=(FileName a, FileName b) { return a.id_ != b.id_; }
  friend bool operator<(FileName a, FileName b) { return a.str() < b.str(); }
  friend bool operator==(FileName a, const std::string& b) { return a.str() == b; }
  friend bool operator==(const std::string& a, FileName b) { return a == b.str(); }
  friend bool operator==(FileName a, const char* b) { return a.str() == b; }

 private:
  std::uint32_t id_ = 0;  ///< 0: the empty name
};

/// A position in a source file. Line and column are 1-based; 0 means unknown.
struct SourceLocation {
  FileName file;
  int line = 0;
  int column = 0;

  bool known() const { return line > 0; }
  friend bool operator==(const SourceLocation& a, const SourceLocation& b) {
    return a.file == b.file && a.line == b.line && a.column == b.column;
  }
  friend bool operator!=(const SourceLocation& a, const SourceLocation& b) { return !(a == b); }
};

/// The first known location of the list (line > 0), else the last one: findings point at the
/// most specific place that was written.
SourceLocation first_known(std::initializer_list<SourceLocation> locations);

/// How far a fix-it may be applied without asking (docs/rules.md, "Fix-its").
enum class FixSafety {
  kSafe,     ///< the model Choreonoid loads stays the same: `bodycheck --fix` applies it
  kUpgrade,  ///< part of the format 1.0 -> 2.0 upgrade: applied only with `--fix --upgrade`
  kUnsafe,   ///< changes what is loaded (e.g. a typo whose key is now read): shown, never applied
};

std::string_view fix_safety_name(FixSafety safety);

/// A fix-it: replace the bytes [begin, end) of `file` (which hold `original`) with
/// `replacement`. `line` and `column` (1-based, bytes) are where `begin` is.
struct FixIt {
  FileName file;
  std::size_t begin = 0;
  std::size_t end = 0;
  int line = 0;
  int column = 0;
  std::string original;
  std::string replacement;
  FixSafety safety = FixSafety::kSafe;

  friend bool operator==(const FixIt& a, const FixIt& b) {
    return a.file == b.file && a.begin == b.begin && a.end == b.end && a.replacement == b.replacement;
  }
};

struct Diagnostic {
  Severity severity = Severity::kError;
  std::string rule_id;  ///< stable kebab-case id from the rule table, e.g. "yaml-duplicate-key"
  std::string message;
  SourceLocation location;
  std::optional<SourceLocation> via;  ///< alias use site when the value came through *anchor
  std::string fix_hint;
  /// A finer kind within the rule, where the rule has kinds (an export loss's: "tracks",
  /// "devices", ...; see converters/core: loss.h); empty otherwise.
  std::string category;
  /// Edits that fix the finding, when the rule knows them exactly (empty otherwise).
  std::vector<FixIt> fixes;
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
#pragma GCC visibility pop
