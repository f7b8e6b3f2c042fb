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

bool check_link_names(const Model& model, DiagnosticSink& sink, std::string_view format) {
  bool usable = true;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& link = model.links[i];
    if (!link.name.empty()) continue;
    usable = false;
    const std::string parent =
        link.parent >= 0 ? fmt::format(" (child of \"{}\")", model.links[static_cast<std::size_t>(link.parent)].name)
                         : std::string(" (the root)");
    report_rule(sink, "export-link-unnamed", link.source,
                fmt::format("link {}{} has no name, which {} needs to refer to it; the model is not written", i, parent,
                            format),
                "add name: LINK_NAME");
  }
  return usable;
}

}  // namespace bodyfmt::converters
