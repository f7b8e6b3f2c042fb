#pragma once
/// The input protection of every tool output that is not an export (bodycheck -o): the same
/// rule as the exporters' OutputSet, for a report written as a stream.
#include <bodyfmt/input_files.h>

#include <string>
#include <vector>

namespace bodyfmt::tools {

/// Why `output` must not be written: it is, or links to (also through a hard link), one of
/// `inputs` ("it is the model of this run ('a.body')"), or it is a folder. Empty when it may
/// be written; a path that does not exist yet may always be.
std::string input_clash(const std::string& output, const std::vector<InputFile>& inputs);

}  // namespace bodyfmt::tools
