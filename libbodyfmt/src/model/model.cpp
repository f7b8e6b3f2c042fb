#include <bodyfmt/model.h>

#include <algorithm>

namespace bodyfmt {

std::string_view joint_type_name(JointType type) {
  switch (type) {
    case JointType::kFree: return "free";
    case JointType::kFixed: return "fixed";
    case JointType::kRevolute: return "revolute";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kPseudoContinuousTrack: return "pseudo_continuous_track";
  }
  return "fixed";
}

std::string_view geometry_type_name(const Geometry& geometry) {
  static constexpr std::string_view kNames[] = {"Box",          "Sphere",    "Cylinder",      "Cone",
                                                "Capsule",      "Extrusion", "ElevationGrid", "IndexedFaceSet",
                                                "TriangleMesh", "Resource"};
  return kNames[geometry.index()];
}

LinkIndex Model::find_link(std::string_view link_name) const {
  for (std::size_t i = 0; i < links.size(); ++i)
    if (links[i].name == link_name) return static_cast<LinkIndex>(i);
  return -1;
}

long long Model::num_joints() const {
  // Choreonoid's joint array holds ids 0..max (gaps become dummy joints).
  int max_id = -1;
  for (const Link& link : links) max_id = std::max(max_id, link.joint_id);
  return static_cast<long long>(max_id) + 1;
}

}  // namespace bodyfmt
