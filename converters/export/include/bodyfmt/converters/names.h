#pragma once
/// Names in XML documents and target formats.
#include <bodyfmt/text.h>

#include <string>
#include <string_view>

namespace bodyfmt::converters {

// XML text quoting is libbodyfmt's (bodyfmt/text.h); the writers name it from here.
using text::is_xml_text;
using text::xml_comment_text;
using text::xml_escape;

/// The name rules ROS tools rely on (tf frame ids, robot_state_publisher, MoveIt): non-empty,
/// starts with a letter or '_', then letters, digits, '_', '-' and '.'. Returns an empty
/// string when `name` is valid, else why it is not.
std::string urdf_name_problem(std::string_view name);

/// A file-name-safe version of `name` (letters, digits, '_', '-', '.'; others become '_').
std::string file_stem(std::string_view name);

}  // namespace bodyfmt::converters
