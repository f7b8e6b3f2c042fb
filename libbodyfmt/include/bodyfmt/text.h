#pragma once
/// Quoting text for the formats the tools write: JSON strings, YAML scalars, XML 1.0 text and
/// paths in URIs. One copy for the reports (JSON, SARIF), the writers (URDF, MJCF, glTF), the
/// language server and any later tool.

#include <bodyfmt/export.h>

#include <string>
#include <string_view>

#pragma GCC visibility push(default)
namespace bodyfmt {
namespace text {

/// JSON text for `s` between quotes: `"` `\` and control characters escaped, UTF-8 kept,
/// invalid UTF-8 bytes replaced by U+FFFD.
std::string json_quote(std::string_view s);

/// A YAML double-quoted scalar that reads back as `s`, for the .body writer and the YAML
/// reports: `"` and `\` escaped, every character outside YAML's printable set (controls, DEL,
/// C1, the byte order mark, U+FFFE/U+FFFF) as \xNN or \uNNNN, tab, LF and CR as \t \n \r, and
/// the line breaks a parser would fold (NEL, U+2028, U+2029) as \N \L \P. An invalid UTF-8 byte
/// becomes U+FFFD.
std::string yaml_quote(std::string_view s);

/// The same escapes without the quotes, `"` and `\` escaped only when `escape_quotes` is set:
/// text for a YAML comment, which no character can then end.
std::string yaml_escape(std::string_view s, bool escape_quotes);

/// Escapes & < > " ' for use in XML attribute values and text. (tinyxml2 escapes attributes
/// itself; this is for hand-written XML and for tests.)
std::string xml_escape(std::string_view text);

/// Text that is safe inside an XML comment: "--" and a trailing "-" are broken up with a
/// space, and characters XML 1.0 forbids are replaced by '?'.
std::string xml_comment_text(std::string_view text);

/// `path` for the path part of a `file:` URI: every byte but RFC 3986's unreserved characters
/// and `/` percent-encoded (upper-case hex), so a name with spaces, `%`, `#` or non-ASCII
/// letters reads back as itself.
std::string uri_path_encode(std::string_view path);

/// The length of the valid UTF-8 sequence that starts at s[i] (1 for ASCII) with its code point
/// in `code_point`; 0 when it is malformed (truncated, overlong, a surrogate, above U+10FFFF).
std::size_t utf8_sequence(std::string_view s, std::size_t i, unsigned& code_point);

/// True when `s` is valid UTF-8.
bool is_utf8(std::string_view s);

/// True when every byte is allowed in an XML 1.0 document (no control characters other than
/// tab, newline and carriage return) and the text is valid UTF-8.
bool is_xml_text(std::string_view text);

}  // namespace text
}  // namespace bodyfmt
#pragma GCC visibility pop
