#pragma once
// How bodydiff prints a list of changes: GCC-style text or its JSON document
// (docs/bodydiff-json.md), and the names the two sides carry in it.

#include <bodyfmt/model_diff.h>

#include <ostream>
#include <string>
#include <vector>

namespace bodyfmt::tools {

/// GCC-style: the line of the new value (the old one's for a removal), then a note at the old.
void write_text(std::ostream& out, const std::vector<ModelChange>& changes, const std::string& old_name,
                const std::string& new_name);

/// One JSON document with every change, both sides' locations and a summary.
void write_json(std::ostream& out, const std::vector<ModelChange>& changes, const std::string& old_name,
                const std::string& new_name, double tolerance);

/// Renames `from` in the old side's locations to `to` (a work-tree path to git's a/ side, or
/// to REV:PATH).
void name_old_side(std::vector<ModelChange>& changes, const std::string& from, const std::string& to);

/// Renames the work-tree path in locations to git's a/ and b/ sides.
void name_sides(std::vector<ModelChange>& changes, const std::string& path);

}  // namespace bodyfmt::tools
