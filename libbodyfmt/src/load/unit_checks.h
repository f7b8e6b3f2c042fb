#pragma once
// Angle values that look written in the other unit (body-format-spec §3), found where they are
// read: only the loader knows each file's own unit and the text that a fix-it edits. The
// thresholds are bodyfmt/unit_heuristics.h's.

#include <bodyfmt/model.h>

#include "load/load_context.h"

namespace bodyfmt::detail {

/// units-range-looks-degree: `range` (a joint_range value) of revolute `link` in a radian file
/// reads [lower, upper] as written and looks like degrees. Its fix-it (unsafe: the model changes)
/// reinterprets the numbers as degrees, writing the radians they stand for.
void check_degree_range(LoadContext& ctx, const Link& link, const yaml::NodeRef& range, double lower, double upper);

/// units-velocity-looks-degree: the same for a max_joint_velocity or joint_velocity_range value.
void check_degree_velocity(LoadContext& ctx, const Link& link, const yaml::NodeRef& limit, double lower, double upper);

/// units-rotation-looks-radian: the angle of an axis-angle rotation in a degree file, written
/// at `angle` as `written`, looks like radians (1.5708). Its fix-it writes the degrees it stands
/// for (90).
void check_radian_rotation(LoadContext& ctx, const yaml::NodeRef& angle, double written);

}  // namespace bodyfmt::detail
