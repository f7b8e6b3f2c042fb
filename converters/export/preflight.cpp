#include <bodyfmt/converters/preflight.h>
#include <bodyfmt/physical.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

bool check_joints(const Model& model, DiagnosticSink& sink, bool reversed_range_writable) {
  bool usable = true;
  // The joint half of the physical-validity gate, which bodycheck's joint rules report too.
  for (const PhysicalFinding& f : assess_joints(model)) {
    const Link& link = model.links[static_cast<std::size_t>(f.link)];
    if (f.defect == PhysicalDefect::kAxisZero) {
      usable = false;
      report_physical(
          sink, f, fmt::format("joint axis of link \"{}\" is the zero vector; the joint cannot be exported", link.name),
          "give the axis a direction, e.g. joint_axis: Z");
    } else if (f.defect == PhysicalDefect::kRangeReversed && reversed_range_writable) {
      // Written back as it came in (a URDF that some simulators read as "no limit"), but never
      // without a word at the range's line.
      report_rule(sink, "export-range-reversed", f.at,
                  fmt::format("joint range of link \"{}\" is reversed (lower > upper); written as it is", link.name),
                  "swap the two bounds if the joint is meant to move between them");
    } else if (f.defect == PhysicalDefect::kRangeReversed) {
      usable = false;
      report_physical(
          sink, f,
          fmt::format("joint range of link \"{}\" is reversed (lower > upper); the joint cannot be exported",
                      link.name),
          "swap the two bounds");
    }
  }
  return usable;
}

}  // namespace bodyfmt::converters
