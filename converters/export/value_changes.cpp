#include <bodyfmt/converters/numbers.h>
#include <bodyfmt/converters/value_changes.h>

#include <fmt/format.h>

namespace bodyfmt::converters {

namespace {
/// "x, y, z", as a .body list writes a vector.
std::string list_text(const Eigen::Vector3d& v) {
  return format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z());
}
}  // namespace

Eigen::Vector3d axis_direction(const Link& link) {
  const double norm = link.joint_axis.norm();
  return norm > 0 ? Eigen::Vector3d(link.joint_axis / norm) : link.joint_axis;
}

std::optional<ValueChange> axis_change(const Model& model, const std::vector<PhysicalFinding>& joint_findings,
                                       std::size_t index, std::string_view reader) {
  for (const PhysicalFinding& f : joint_findings) {
    if (f.defect != PhysicalDefect::kAxisNotUnit || f.link != static_cast<LinkIndex>(index)) continue;
    const Link& link = model.links[index];
    return ValueChange{
        f.at, fmt::format("the joint axis [{}] of link \"{}\" is not a unit vector (length {}); written as its "
                          "direction [{}]: {} reads an axis as a direction, while Choreonoid uses it as given and "
                          "scales the joint's displacement and velocity by its length",
                          list_text(link.joint_axis), link.name, format_number(link.joint_axis.norm()),
                          list_text(axis_direction(link)), reader)};
  }
  return std::nullopt;
}

}  // namespace bodyfmt::converters
