#include <bodyfmt/model_diff.h>

#include "diff/model_fields.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace bodyfmt {
namespace {

using detail::Field;
using detail::LinkFields;

constexpr double kDegree = 180.0 / 3.14159265358979323846;

ModelChange change(ChangeKind kind, std::string link, const Field* a, const Field* b) {
  ModelChange c;
  c.kind = kind;
  c.link = std::move(link);
  c.field = (a ? a : b)->key;
  c.derived = (a ? a : b)->derived;
  if (a) c.old_value = detail::field_value(*a), c.old_source = a->source;
  if (b) c.new_value = detail::field_value(*b), c.new_source = b->source;
  return c;
}

// How far a world frame moved, for the reviewer: the distance and the angle of rotation.
std::string displacement(const Field& a, const Field& b) {
  const Eigen::Vector3d pa(a.numbers[0], a.numbers[1], a.numbers[2]), pb(b.numbers[0], b.numbers[1], b.numbers[2]);
  Eigen::Matrix3d Ra, Rb;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Ra(r, c) = a.numbers[3 + 3 * r + c], Rb(r, c) = b.numbers[3 + 3 * r + c];
  const double cosine = std::clamp(((Ra.transpose() * Rb).trace() - 1) / 2, -1.0, 1.0);
  return fmt::format(" (moved {} m, turned {} deg)", (pb - pa).norm(), std::acos(cosine) * kDegree);
}

void diff_fields(const std::vector<Field>& old_fields, const std::vector<Field>& new_fields, const std::string& link,
                 double tolerance, std::vector<ModelChange>& out) {
  std::map<std::string_view, const Field*> old_by_key;
  for (const Field& f : old_fields) old_by_key.emplace(f.key, &f);
  std::map<std::string_view, bool> seen;
  std::map<std::string_view, bool> new_elements;
  for (const Field& b : new_fields)
    if (!b.element.empty()) new_elements[b.element] = true;
  std::map<std::string_view, bool> old_elements;
  for (const Field& a : old_fields)
    if (!a.element.empty()) old_elements[a.element] = true;
  // A whole element added or removed is one change, at its first field, named after it.
  std::map<std::string_view, bool> reported;
  auto whole = [&](const Field& f, const std::map<std::string_view, bool>& other_side) {
    return !f.element.empty() && !other_side.count(f.element);
  };
  auto element_change = [&](ChangeKind kind, const Field* a, const Field* b) {
    const Field& f = a ? *a : *b;
    if (reported[f.element]) return;
    reported[f.element] = true;
    out.push_back(change(kind, link, a, b));
    out.back().field = f.element;
  };
  // A shape whose geometry type changed: the type is the change, not each size it has or had.
  std::map<std::string_view, bool> retyped;
  for (const Field& b : new_fields)
    if (!b.element.empty() && b.key == b.element + " geometry")
      if (auto it = old_by_key.find(b.key); it != old_by_key.end() && it->second->text != b.text)
        retyped[b.element] = true;
  auto hidden = [&](const Field& f) { return f.geometry_detail && retyped.count(f.element); };
  for (const Field& b : new_fields) {
    seen[b.key] = true;
    if (hidden(b)) continue;
    if (whole(b, old_elements)) {
      element_change(ChangeKind::kAdded, nullptr, &b);
      continue;
    }
    auto it = old_by_key.find(b.key);
    if (it == old_by_key.end()) {
      out.push_back(change(ChangeKind::kAdded, link, nullptr, &b));
    } else if (!detail::same_value(*it->second, b, tolerance)) {
      out.push_back(change(ChangeKind::kChanged, link, it->second, &b));
      if (b.key == "world_frame") out.back().new_value += displacement(*it->second, b);
    }
  }
  for (const Field& a : old_fields) {
    if (seen.count(a.key) || hidden(a)) continue;
    if (whole(a, new_elements))
      element_change(ChangeKind::kRemoved, &a, nullptr);
    else
      out.push_back(change(ChangeKind::kRemoved, link, &a, nullptr));
  }
}

}  // namespace

std::vector<ModelChange> diff_models(const Model& old_model, const Model& new_model, const ModelDiffOptions& options) {
  const detail::ModelFields a = detail::collect_fields(old_model, options.derived);
  const detail::ModelFields b = detail::collect_fields(new_model, options.derived);
  std::vector<ModelChange> out;
  diff_fields(a.model, b.model, "", options.tolerance, out);

  std::map<std::string_view, const LinkFields*> old_links;
  for (const LinkFields& l : a.links) old_links.emplace(l.name, &l);
  std::map<std::string_view, bool> matched;
  for (const LinkFields& l : b.links) {
    auto it = old_links.find(l.name);
    if (it == old_links.end()) {
      ModelChange c;
      c.kind = ChangeKind::kAdded;
      c.link = l.name;
      c.field = "link";
      c.new_value = l.summary;
      c.new_source = l.source;
      out.push_back(std::move(c));
      continue;
    }
    matched[l.name] = true;
    diff_fields(it->second->fields, l.fields, l.name, options.tolerance, out);
  }
  for (const LinkFields& l : a.links) {
    if (matched.count(l.name)) continue;
    ModelChange c;
    c.kind = ChangeKind::kRemoved;
    c.link = l.name;
    c.field = "link";
    c.old_value = l.summary;
    c.old_source = l.source;
    out.push_back(std::move(c));
  }
  return out;
}

std::string canonical_text(const Model& model) {
  constexpr int kDigits = 12;
  const detail::ModelFields fields = detail::collect_fields(model, true);
  std::string out;
  for (const Field& f : fields.model) out += fmt::format("{}: {}\n", f.key, detail::field_value(f, kDigits));
  std::vector<const LinkFields*> links;
  for (const LinkFields& l : fields.links) links.push_back(&l);
  std::stable_sort(links.begin(), links.end(),
                   [](const LinkFields* x, const LinkFields* y) { return x->name < y->name; });
  for (const LinkFields* l : links) {
    out += fmt::format("\nlink '{}'\n", l->name);
    std::vector<const Field*> sorted;
    for (const Field& f : l->fields) sorted.push_back(&f);
    // Devices sorted by name; the link's own fields keep their fixed order.
    std::stable_sort(sorted.begin(), sorted.end(), [](const Field* x, const Field* y) {
      const bool dx = x->key.rfind("device ", 0) == 0, dy = y->key.rfind("device ", 0) == 0;
      if (dx != dy) return dy;
      return dx && x->key.substr(0, x->key.find(' ', 8)) < y->key.substr(0, y->key.find(' ', 8));
    });
    for (const Field* f : sorted) out += fmt::format("  {}: {}\n", f->key, detail::field_value(*f, kDigits));
  }
  return out;
}

}  // namespace bodyfmt
