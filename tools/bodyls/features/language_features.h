#pragma once
/// What bodyls answers about one document besides its diagnostics and fix-its: hover,
/// completion, go to definition, references, rename and the document's symbols.
///
/// Positions are the project's own: 1-based lines and 1-based byte columns, as SourceLocation
/// has them. The server converts them to and from the protocol's 0-based UTF-16 positions, so
/// nothing here knows about UTF-16.

#include <bodyfmt/model.h>

#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::lsp {

struct TextPoint {
  int line = 1;    ///< 1-based
  int column = 1;  ///< 1-based, in bytes
};

/// [begin, end): end is the point just after the last byte.
struct TextRange {
  TextPoint begin;
  TextPoint end;
};

/// A range in a file: `file` is the path as the loader names it (the document's own path, or a
/// SubBody, YAML resource or mesh file it refers to).
struct FileRange {
  std::string file;
  TextRange range;
  /// The model knows where a name begins, not where it ends: the range is then the token that
  /// begins at range.begin in the file's text (as a finding's), which the server finds in the
  /// text the model was read from.
  bool to_token_end = false;
};

/// One open document as the features see it.
struct Document {
  std::string path;  ///< absolute path of the buffer (it may be unsaved)
  std::string text;  ///< the buffer as it is now
  /// The model of the buffer's last text that loaded (null when none has): it may be of an
  /// older text than `text` while the user types, which `model_is_current` tells.
  const Model* model = nullptr;
  bool model_is_current = false;
};

struct Hover {
  std::string markdown;
  std::string plain_text;  ///< the same without markup, for a client that renders no Markdown
  TextRange range;         ///< the key or value hovered
};

/// On a key: what it means, its unit (an angle's as the file reads it: degree or radian), its
/// default and where docs/keys.md lists it. On a number under an angle key: its
/// value in degrees and in radians as the file's format reads it. On a link's name: its mass,
/// its subtree's combined mass, its joint type and its world frame at the initial pose.
std::optional<Hover> hover(const Document& document, TextPoint at);

enum class CompletionKind { kKey, kValue, kLinkName, kAnchor, kFile };

struct CompletionItem {
  std::string label;
  std::string insert_text;
  std::string detail;  ///< one line: the key's meaning and unit, the link's parent, ...
  CompletionKind kind = CompletionKind::kKey;
  TextRange replace;  ///< the text the item replaces (the partial word at the cursor)
};

/// The keys valid at `at` in snake_case (none already present in that mapping), the values of
/// enumerations (joint_type, an element's type, actuation_mode), link names after `parent:`,
/// anchors after `*`, files after `uri:`.
std::vector<CompletionItem> complete(const Document& document, TextPoint at);

/// `parent: X` (and root_link, link1_name, link2_name) -> link X's name: in this text, or
/// where the model read it (a SubBody file, nested ones too, with the SubBody's prefix and
/// suffix in X; a ContinuousTrack's template); `*a` -> `&a`; a `uri` value -> the file it names
/// (a SubBody's model too). Empty when nothing is defined at `at`.
std::vector<FileRange> definition(const Document& document, TextPoint at);

/// On a link's name or a `parent:` value naming it: every `parent:` value naming the link,
/// and the link's `name` value when `include_declaration`.
std::vector<FileRange> references(const Document& document, TextPoint at, bool include_declaration);

struct TextEdit {
  FileRange where;
  std::string new_text;
};

/// The range of the link name at `at` that a rename would change, or nullopt (then `why` says
/// what the cursor is on).
std::optional<TextRange> prepare_rename(const Document& document, TextPoint at, std::string& why);

/// The edits that rename the link at `at` to `new_name`: its `name` value and every `parent:`
/// value naming it. nullopt with `why` when the cursor is on no link name, or `new_name` is
/// not a name the loader would accept or is already taken.
std::optional<std::vector<TextEdit>> rename_link(const Document& document, TextPoint at, const std::string& new_name,
                                                 std::string& why);

enum class SymbolKind { kBody, kLink, kDevice, kElement };

struct Symbol {
  std::string name;
  std::string detail;  ///< the joint type, the device or element type
  SymbolKind kind = SymbolKind::kLink;
  TextRange range;      ///< the whole item
  TextRange selection;  ///< its name
  std::vector<Symbol> children;
};

/// The link tree, with each link's devices and elements under it.
std::vector<Symbol> document_symbols(const Document& document);

}  // namespace bodyfmt::lsp
