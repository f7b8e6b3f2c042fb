#pragma once
/// Fix-its applied to text (`bodycheck --fix`): edits of exact byte ranges, the unified diff
/// that `--fix --dry-run` prints, and the comparison that proves a fixed file describes the
/// same model as the original before it is written.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

/// `text` with `fixes` (all of one file) applied. Identical edits (text shared through an
/// alias, reported once per use) are applied once. Returns nullopt with `why` set when an edit
/// does not fit the text (out of range, or the bytes differ from its `original`: the file
/// changed since it was read) or two different edits overlap. Bytes outside the edited ranges
/// are kept as they are.
std::optional<std::string> apply_fixes(std::string_view text, std::vector<FixIt> fixes, std::string& why);

/// A unified diff (`diff -u` format, 3 lines of context) from `before` to `after`, with the
/// headers `--- a/NAME` and `+++ b/NAME`; empty when the texts are equal.
std::string unified_diff(std::string_view before, std::string_view after, const std::string& name);

/// The first difference between two loaded models, in words ("link \"ARM\": joint_range_upper
/// 1.5 != 1.6"), or nullopt when they are the same model: names, tree, joints, offsets, mass
/// data, shapes and geometry, appearance, devices and extra joints, numbers equal within
/// `relative_tolerance` (relative to the larger magnitude, absolute below 1). Ignored: source
/// locations, the file's format_version and angle unit, and the spelling of device keys.
std::optional<std::string> model_difference(const Model& a, const Model& b, double relative_tolerance = 1e-12);

}  // namespace bodyfmt
#pragma GCC visibility pop
