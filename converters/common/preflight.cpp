#include <bodyfmt/converters/preflight.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

bool check_joints(const Model& model, DiagnosticSink& sink) {
  bool usable = true;
  for (const Link& link : model.links) {
    const bool has_axis = link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic ||
                          link.joint_type == JointType::kPseudoContinuousTrack;
    if (!has_axis) continue;
    // The same conditions as bodycheck's rules (validate/rules/joints.cpp).
    if (link.joint_axis.norm() < 1e-9) {
      usable = false;
      report_rule(sink, "joint-axis-zero", source_of(link, LinkSources::kJointAxis),
                  fmt::format("joint axis of link \"{}\" is the zero vector; the joint cannot be exported", link.name),
                  "give the axis a direction, e.g. joint_axis: Z");
    }
    if (link.joint_type != JointType::kPseudoContinuousTrack && link.joint_range_lower > link.joint_range_upper) {
      usable = false;
      report_rule(sink, "joint-range-reversed", source_of(link, LinkSources::kJointRange),
                  fmt::format("joint range of link \"{}\" is reversed (lower > upper); the joint cannot be exported",
                              link.name),
                  "swap the two bounds");
    }
  }
  return usable;
}

}  // namespace bodyfmt::converters
