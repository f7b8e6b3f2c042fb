#pragma once
/// What no export can write faithfully, checked by every writer before it writes anything.
/// Choreonoid loads these models (bodycheck reports them), but a joint without a direction
/// or a range whose lower bound is above its upper one has no meaning in URDF or MJCF: MuJoCo
/// refuses both, and URDF consumers divide by the axis length or clamp to an empty interval.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

namespace bodyfmt::converters {

/// Reports, as errors at the value, every revolute, prismatic or track joint whose axis is the
/// zero vector (`joint-axis-zero`) and, unless `reversed_range_writable` (URDF holds such a range
/// as written, and files written for simulators use it), every joint range with lower > upper
/// (`joint-range-reversed`); returns false if there was one.
bool check_joints(const Model& model, DiagnosticSink& sink, bool reversed_range_writable = false);

}  // namespace bodyfmt::converters
