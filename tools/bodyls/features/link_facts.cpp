#include "link_facts.h"

#include <bodyfmt/angles.h>
#include <bodyfmt/derived.h>

#include <fmt/format.h>

#include <cmath>
#include <vector>

namespace bodyfmt::lsp {

std::optional<HoverText> link_hover(const Document& document, std::string_view name) {
  const Model* model = document.model;
  if (!model || model->links.empty()) return std::nullopt;
  const LinkIndex index = model->find_link(name);
  if (index < 0 || index >= static_cast<LinkIndex>(model->links.size())) return std::nullopt;
  const Link& link = model->links[static_cast<std::size_t>(index)];
  const double mass = compute_mass_properties(link).mass;
  // The subtree: links are in depth-first pre-order, but a walk of the children does not
  // depend on that.
  double subtree_mass = 0;
  std::vector<LinkIndex> stack = {index};
  std::size_t visited = 0;
  while (!stack.empty() && visited <= model->links.size()) {
    const LinkIndex i = stack.back();
    stack.pop_back();
    ++visited;
    const Link& l = model->links[static_cast<std::size_t>(i)];
    subtree_mass += compute_mass_properties(l).mass;
    for (LinkIndex child : l.children)
      if (child >= 0 && child < static_cast<LinkIndex>(model->links.size())) stack.push_back(child);
  }
  // The initial pose: the root where the file puts it, each joint at its initial displacement
  // (joint_angle, joint_displacement), as Choreonoid poses a body it has just loaded.
  std::vector<double> q(model->links.size(), 0.0);
  for (std::size_t i = 0; i < model->links.size(); ++i) q[i] = model->links[i].initial_displacement;
  const std::vector<Eigen::Isometry3d> frames = compute_world_frames(*model, q);
  const Eigen::Isometry3d& X = frames[static_cast<std::size_t>(index)];
  const Eigen::AngleAxisd rotation(X.linear());
  // What is left of a zero by rounding (cos 90 degrees = 6e-17), and -0, print as 0.
  const auto clean = [](Eigen::Vector3d v) {
    for (double& x : v) x = std::abs(x) < 1e-12 ? 0.0 : x;
    return v;
  };
  const Eigen::Vector3d p = clean(X.translation());
  const Eigen::Vector3d a = clean(rotation.axis());
  HoverText out;
  out.bold("link " + link.name).text(fmt::format(" — joint {}", joint_type_name(link.joint_type)));
  if (link.parent >= 0) out.text(", parent " + model->links[static_cast<std::size_t>(link.parent)].name);
  out.paragraph().text(fmt::format("mass {:.6g} kg; with its subtree {:.6g} kg", mass, subtree_mass)).paragraph();
  out.text(
      fmt::format("world frame at the initial pose: position [{:.6g}, {:.6g}, {:.6g}] m, rotation [{:.6g}, "
                  "{:.6g}, {:.6g}, {:.6g}°]",
                  p.x(), p.y(), p.z(), a.x(), a.y(), a.z(), rotation.angle() * 180 / kPi));
  if (!document.model_is_current) out.paragraph().text("(from the last text that loaded)");
  return out;
}

}  // namespace bodyfmt::lsp
