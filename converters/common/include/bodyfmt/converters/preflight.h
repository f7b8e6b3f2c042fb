#pragma once
/// What no export can write faithfully, checked by every writer before it writes anything.
/// Choreonoid loads these models (bodycheck reports them), but a joint without a direction
/// has no meaning in URDF or MJCF: urdfdom and MuJoCo refuse it or divide by zero.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

namespace bodyfmt::converters {

/// Reports `joint-axis-zero` (an error, at the joint_axis value) for every revolute,
/// prismatic or track joint whose axis is the zero vector; returns false if there was one.
bool check_joint_axes(const Model& model, DiagnosticSink& sink);

}  // namespace bodyfmt::converters
