#include <bodyfmt/model.h>

#include <algorithm>
#include <iterator>

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

bool is_one_dof(const Link& link) {
  return link.joint_type == JointType::kRevolute || link.joint_type == JointType::kPrismatic;
}

std::string_view geometry_type_name(const Geometry& geometry) {
  static constexpr std::string_view kNames[] = {"Box",          "Sphere",    "Cylinder",      "Cone",
                                                "Capsule",      "Extrusion", "ElevationGrid", "IndexedFaceSet",
                                                "TriangleMesh", "Resource"};
  return kNames[geometry.index()];
}

LinkSources::LinkSources(const LinkSources& other) : file_(other.file_), in_file_(other.in_file_) {
  std::copy(std::begin(other.at_), std::end(other.at_), std::begin(at_));
  if (other.other_files_) {
    other_files_ = std::make_unique<FileName[]>(kFieldCount);
    std::copy_n(other.other_files_.get(), kFieldCount, other_files_.get());
  }
}

LinkSources& LinkSources::operator=(const LinkSources& other) { return *this = LinkSources(other); }

SourceLocation LinkSources::get(Field field) const {
  const Position& at = at_[field];
  const FileName file = (in_file_ >> field) & 1 ? file_ : other_files_ ? other_files_[field] : FileName();
  return SourceLocation{file, at.line, at.column};
}

void LinkSources::set(Field field, const SourceLocation& at) {
  at_[field] = Position{at.line, at.column};
  const auto bit = static_cast<std::uint16_t>(1u << field);
  if (!at.file.empty() && file_.empty()) file_ = at.file;
  if (!at.file.empty() && at.file == file_) {
    in_file_ |= bit;
    return;
  }
  in_file_ &= static_cast<std::uint16_t>(~bit);
  if (!other_files_ && !at.file.empty()) other_files_ = std::make_unique<FileName[]>(kFieldCount);
  if (other_files_) other_files_[field] = at.file;
}

SourceLocation source_of(const Link& link, LinkSources::Field field) {
  return first_known({link.sources.get(field), link.source});
}

SourceLocation rigid_body_source(const Link& link) {
  for (const MassContribution& c : link.mass_contributions)
    if (!c.from_link_keys && c.source.known()) return c.source;
  return {};
}

SourceLocation inertia_source(const Link& link) {
  return first_known({link.sources.inertia(), rigid_body_source(link), link.sources.mass(), link.source});
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
