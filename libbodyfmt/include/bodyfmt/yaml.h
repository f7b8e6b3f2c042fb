#pragma once
/// YAML inputs other than models (`.bodycheck.yaml`, bodysim scenarios, any later tool's
/// input), read the way model files are: the same bounded reader (only a regular file, up to a
/// size limit checked before anything is read, so a FIFO or /dev/zero is refused at once), the
/// same YAML dialect and limits (every scalar a string, merge keys applied, an alias and depth
/// budget), and every problem a located diagnostic, `file:line:col` 1-based.
///
///   CollectingSink sink;
///   std::optional<YamlDocument> doc = read_yaml_file("run.yaml", sink);
///   YamlReader r(sink, "dynamics-scenario");
///   if (doc && r.mapping(doc->root(), "a scenario")) {
///     r.known_keys(doc->root(), {"duration"}, "a scenario");
///     if (std::optional<YamlEntry> d = doc->root().find("duration")) r.number(d->value, "'duration'");
///   }

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// The limits a YAML input is read within; the defaults are the model loader's (LoadOptions).
struct YamlLimits {
  /// Largest file read; only regular files are read, never a device, a FIFO or a directory.
  std::uintmax_t max_file_bytes = 256u << 20;
  /// "Billion laughs" guard: the document's node count with every alias expanded.
  std::size_t max_expanded_nodes = 40'000'000;
  /// Nesting limit for sequences and mappings, counted through aliases.
  int max_depth = 200;
};

struct YamlEntry;

/// A node of a YamlDocument, valid while the document lives. Every scalar is a string as
/// written (body-format-spec §1.1); YamlReader converts it. A node reached through an alias
/// is located where the alias is written.
class YamlNode {
 public:
  YamlNode() = default;
  /// False for the node of a failed find() or of a default-constructed YamlNode.
  explicit operator bool() const { return node_ != nullptr; }

  bool is_scalar() const;
  bool is_sequence() const;
  bool is_mapping() const;
  /// A plain empty scalar, `~` or `null` (`key:` with no value).
  bool is_null() const;
  /// The scalar's text; empty for a collection.
  std::string_view scalar() const;
  /// Where the node is written (its alias when it was reached through one).
  const SourceLocation& location() const;
  /// A sequence's items in order; empty otherwise.
  std::vector<YamlNode> items() const;
  /// A mapping's entries in file order, merge keys applied and duplicate keys collapsed (the
  /// last wins, a `yaml-duplicate-key` warning was reported); empty otherwise.
  std::vector<YamlEntry> entries() const;
  /// The entry of `key` in a mapping; nullopt when absent or when this is not a mapping.
  std::optional<YamlEntry> find(std::string_view key) const;

 private:
  friend struct YamlNodeAccess;  // the library's side, which makes nodes of its YAML tree
  const void* node_ = nullptr;
  const SourceLocation* site_ = nullptr;
};

struct YamlEntry {
  std::string_view key;
  SourceLocation key_location;
  YamlNode value;
};

/// A parsed document. Owns every node; YamlNodes read from it are valid while it lives.
class YamlDocument {
 public:
  YamlDocument(YamlDocument&&) noexcept;
  YamlDocument& operator=(YamlDocument&&) noexcept;
  ~YamlDocument();

  /// The first document's root; a text without a document (empty, only comments) has a null
  /// scalar root at 1:1.
  YamlNode root() const;
  /// The file name its locations carry.
  const std::string& file() const;

 private:
  friend struct YamlNodeAccess;
  struct Impl;
  explicit YamlDocument(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Parses the first document of `text`; `file_name` is used in locations. Reports `yaml-*`
/// diagnostics; returns nullopt when nothing usable was built (a syntax error, an undefined
/// alias, a budget exceeded). Warnings (a duplicate key) leave the document usable.
std::optional<YamlDocument> parse_yaml_text(std::string_view text, const std::string& file_name, DiagnosticSink& sink,
                                            const YamlLimits& limits = {});

/// Reads `path` with the model loader's bounded reader and parses it. A file that cannot be
/// read (missing, a directory, a FIFO, a device, over `limits.max_file_bytes`) is reported as
/// `io-read` at `path`: "cannot read WHAT: why", WHAT being `what` or else the quoted path.
std::optional<YamlDocument> read_yaml_file(const std::string& path, DiagnosticSink& sink, const YamlLimits& limits = {},
                                           std::string_view what = {});

/// Reads the values of one YAML input, reporting each problem with one rule id (a row of the
/// rule table, e.g. "config-invalid") at the line and column of the value or key at fault.
/// `what` names the value in messages as the user wrote it ("'duration'", "a command").
class YamlReader {
 public:
  YamlReader(DiagnosticSink& sink, std::string rule_id);

  /// Nothing has been reported through this reader.
  bool ok() const { return ok_; }
  void error(const SourceLocation& at, std::string message, std::string hint = {});
  void error(const YamlNode& at, std::string message, std::string hint = {}) {
    error(at.location(), std::move(message), std::move(hint));
  }

  /// True for a mapping; otherwise reports "WHAT must be a mapping".
  bool mapping(const YamlNode& node, std::string_view what);
  /// True for a sequence; otherwise reports "WHAT must be a list".
  bool sequence(const YamlNode& node, std::string_view what);
  /// A scalar's text; otherwise reports "WHAT must be a single value, not a list or a mapping".
  std::optional<std::string_view> scalar(const YamlNode& node, std::string_view what);
  /// A whole, finite number (`1.5`, `-2e-3`); otherwise reports "WHAT must be a number".
  std::optional<double> number(const YamlNode& node, std::string_view what);
  /// A YAML 1.1 boolean word (true/false, yes/no, on/off, y/n, in three cases, as the model
  /// files read them); otherwise reports "WHAT must be true or false".
  std::optional<bool> boolean(const YamlNode& node, std::string_view what);
  /// Reports each key of `mapping` that is not one of `keys`, at the key: "unknown key 'K' in
  /// WHAT", with "; did you mean 'X'?" when it is a plausible typo of one, and the hint
  /// "keys: ..." listing `keys`. Returns false when there was one.
  bool known_keys(const YamlNode& mapping, const std::vector<std::string_view>& keys, std::string_view what);

 private:
  DiagnosticSink& sink_;
  std::string rule_id_;
  bool ok_ = true;
};

/// The entries of `mapping` whose key is not one of `keys`, in file order.
std::vector<YamlEntry> unknown_keys(const YamlNode& mapping, const std::vector<std::string_view>& keys);

/// The one of `candidates` that `word` is a plausible typo of (the loader's did-you-mean:
/// case-insensitive edit distance, adjacent transpositions counting once), else empty.
std::string_view did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace bodyfmt
#pragma GCC visibility pop
