#pragma once
// Helpers shared by the exporter tests (tests/unit/converters/*): files, scratch folders, and
// the lines a test model marks against the lines diagnostics were reported at.
#include <bodyfmt/diagnostic.h>

#include <filesystem>
#include <string>
#include <vector>

namespace bodyfmt::test {

/// The whole file (empty when it cannot be read).
std::string read(const std::filesystem::path& path);

/// An empty scratch folder under the temporary directory, unique to this process and `name`.
std::filesystem::path fresh_dir(const std::string& name);

/// The 1-based lines of `file` that contain `marker` outside a whole-line comment (a test model
/// marks with a trailing `# loss` comment where a finding must be reported).
std::vector<int> marked_lines(const std::filesystem::path& file, const std::string& marker);

/// The lines `rule` was reported at, sorted.
std::vector<int> reported_lines(const std::vector<Diagnostic>& diagnostics, const std::string& rule);

}  // namespace bodyfmt::test
