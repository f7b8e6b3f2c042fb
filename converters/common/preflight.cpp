#include <bodyfmt/converters/preflight.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

bool check_joint_axes(const Model& model, DiagnosticSink& sink) {
  bool usable = true;
  for (const Link& link : model.links) {
    const bool has_axis = link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic ||
                          link.joint_type == JointType::kPseudoContinuousTrack;
    // The same threshold as bodycheck's rule (validate/rules/joints.cpp).
    if (!has_axis || link.joint_axis.norm() >= 1e-9) continue;
    usable = false;
    report_rule(sink, "joint-axis-zero", link.sources.joint_axis.known() ? link.sources.joint_axis : link.source,
                fmt::format("joint axis of link \"{}\" is the zero vector; the joint cannot be exported", link.name),
                "give the axis a direction, e.g. joint_axis: Z");
  }
  return usable;
}

}  // namespace bodyfmt::converters
