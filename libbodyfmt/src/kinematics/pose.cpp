#include <bodyfmt/derived.h>
#include <bodyfmt/pose.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

namespace bodyfmt {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view joint_name_of(const Link& link) {
  return link.joint_name.empty() ? std::string_view(link.name) : link.joint_name.view();
}

std::vector<LinkIndex> movable_joints(const Model& model) {
  std::vector<LinkIndex> joints;
  for (std::size_t i = 0; i < model.links.size(); ++i)
    if (is_one_dof(model.links[i])) joints.push_back(static_cast<LinkIndex>(i));
  return joints;
}

JointVector joint_vector(const Model& model, const std::vector<JointPosition>& positions) {
  JointVector result;
  result.q.assign(model.links.size(), 0.0);
  // Joint names first: a link named like another link's joint is set through that joint.
  std::unordered_map<std::string_view, std::size_t> by_joint, by_link;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    by_joint.emplace(joint_name_of(model.links[i]), i);
    by_link.emplace(model.links[i].name, i);
  }
  for (const JointPosition& p : positions) {
    auto it = by_joint.find(p.name);
    const bool found = it != by_joint.end() || (it = by_link.find(p.name)) != by_link.end();
    if (!found) {
      result.problems.push_back("no joint or link named '" + p.name + "'");
    } else if (!is_one_dof(model.links[it->second])) {
      result.problems.push_back("joint '" + p.name + "' is " +
                                std::string(joint_type_name(model.links[it->second].joint_type)) +
                                ", not revolute or prismatic");
    } else if (!std::isfinite(p.value)) {
      result.problems.push_back("the position of joint '" + p.name + "' is not finite");
    } else {
      result.q[it->second] = p.value;
    }
  }
  return result;
}

std::pair<std::vector<JointPosition>, std::vector<std::string>> parse_joint_positions(std::string_view text) {
  std::vector<JointPosition> positions;
  std::vector<std::string> problems;
  if (trim(text).empty()) return {positions, problems};
  for (std::size_t begin = 0; begin <= text.size();) {
    std::size_t end = text.find(',', begin);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view item = trim(text.substr(begin, end - begin));
    const std::size_t eq = item.rfind('=');
    const std::string value(eq == std::string_view::npos ? std::string_view() : trim(item.substr(eq + 1)));
    char* stop = nullptr;
    errno = 0;
    const double v = value.empty() ? 0.0 : std::strtod(value.c_str(), &stop);
    if (eq == std::string_view::npos || eq == 0 || value.empty() || *stop != '\0' || errno == ERANGE ||
        !std::isfinite(v)) {
      problems.push_back("'" + std::string(item) + "' is not NAME=VALUE with a finite number");
    } else {
      positions.push_back({std::string(trim(item.substr(0, eq))), v});
    }
    begin = end + 1;
  }
  return {positions, problems};
}

std::vector<Eigen::Isometry3d> forward_kinematics(const Model& model, const std::vector<JointPosition>& positions) {
  return compute_world_frames(model, joint_vector(model, positions).q);
}

}  // namespace bodyfmt
