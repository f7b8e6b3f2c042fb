#pragma once
/// What no export can write faithfully, checked by every writer before it writes anything.
/// Choreonoid loads these models (bodycheck reports them), but a joint without a direction
/// or a range whose lower bound is above its upper one has no meaning in URDF or MJCF: MuJoCo
/// refuses both, and URDF consumers divide by the axis length or clamp to an empty interval.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <string_view>

namespace bodyfmt::converters {

/// Reports, as errors at the value, every revolute, prismatic or track joint whose axis is the
/// zero vector (`joint-axis-zero`) and, unless `reversed_range_writable` (URDF holds such a range
/// as written, and files written for simulators use it), every joint range with lower > upper
/// (`joint-range-reversed`); returns false if there was one.
bool check_joints(const Model& model, DiagnosticSink& sink, bool reversed_range_writable = false);

/// Reports every link without a name (`export-link-unnamed`, an error at the link): Choreonoid
/// loads one, but URDF and MJCF name the links their joints, parents and contact exclusions
/// refer to, and a name made up here would be one the model does not have. False if there was one.
bool check_link_names(const Model& model, DiagnosticSink& sink, std::string_view format);

}  // namespace bodyfmt::converters
