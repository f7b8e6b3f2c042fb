#pragma once
/// Names in XML documents and target formats.
#include <string>
#include <string_view>

namespace bodyfmt::converters {

/// Escapes & < > " ' for use in XML attribute values and text. (tinyxml2 escapes attributes
/// itself; this is for hand-written XML and for tests.)
std::string xml_escape(std::string_view text);

/// Text that is safe inside an XML comment: "--" and a trailing "-" are broken up with a
/// space, and characters XML 1.0 forbids are replaced by '?'.
std::string xml_comment_text(std::string_view text);

/// True when every byte is allowed in an XML 1.0 document (no control characters other than
/// tab, newline and carriage return) and the text is valid UTF-8.
bool is_xml_text(std::string_view text);

/// The name rules ROS tools rely on (tf frame ids, robot_state_publisher, MoveIt): non-empty,
/// starts with a letter or '_', then letters, digits, '_', '-' and '.'. Returns an empty
/// string when `name` is valid, else why it is not.
std::string urdf_name_problem(std::string_view name);

/// A file-name-safe version of `name` (letters, digits, '_', '-', '.'; others become '_').
std::string file_stem(std::string_view name);

}  // namespace bodyfmt::converters
