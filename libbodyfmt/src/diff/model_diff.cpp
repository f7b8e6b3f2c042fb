#include <bodyfmt/model_diff.h>

#include <bodyfmt/angles.h>

#include "fields/field_collector.h"
#include "fields/field_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>
#include <vector>

namespace bodyfmt {
namespace {

using detail::Field;
using detail::LinkFields;

constexpr double kDegree = 180.0 / kPi;

ModelChange change(ChangeKind kind, std::string link, const Field* a, const Field* b) {
  ModelChange c;
  c.kind = kind;
  c.link = std::move(link);
  c.field = (a ? a : b)->key;
  c.derived = (a ? a : b)->derived();
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
  auto hidden = [&](const Field& f) { return f.geometry_detail() && retyped.count(f.element); };
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

// Pairs a link's shapes by content before by rank: elements reordered in the file (a Transform
// moved above another) are no change, and an inserted shape is one shape added, not every later
// shape changed. The new link's shapes are renamed after the old ones they pair with; a shape
// with no pair gets a rank past the old ones (added).
void pair_shapes(const std::vector<Field>& old_fields, std::vector<Field>& new_fields) {
  struct ShapeText {
    std::string element;
    std::string text;
  };
  auto shapes = [](const std::vector<Field>& fields) {
    std::vector<ShapeText> out;
    for (const Field& f : fields) {
      if (f.element.rfind("shape ", 0) != 0) continue;
      if (out.empty() || out.back().element != f.element) out.push_back({f.element, {}});
      out.back().text += f.key.substr(f.element.size()) + "=" + detail::field_value(f, 12) + ";";
    }
    return out;
  };
  const std::vector<ShapeText> before = shapes(old_fields), after = shapes(new_fields);
  if (before.empty() || after.empty()) return;
  std::vector<int> pair(after.size(), -1);
  std::vector<bool> used(before.size(), false);
  auto take = [&](std::size_t i, std::size_t j) { pair[i] = static_cast<int>(j), used[j] = true; };
  for (std::size_t i = 0; i < after.size() && i < before.size(); ++i)
    if (after[i].text == before[i].text) take(i, i);
  for (std::size_t i = 0; i < after.size(); ++i)
    for (std::size_t j = 0; j < before.size() && pair[i] < 0; ++j)
      if (!used[j] && after[i].text == before[j].text) take(i, j);
  for (std::size_t i = 0; i < after.size() && i < before.size(); ++i)
    if (pair[i] < 0 && !used[i]) take(i, i);
  std::map<std::string, std::string, std::less<>> renamed;
  std::size_t next = before.size();
  for (std::size_t i = 0; i < after.size(); ++i) {
    const std::string name = pair[i] >= 0 ? before[pair[i]].element : fmt::format("shape {}", next++);
    if (name != after[i].element) renamed.emplace(after[i].element, name);
  }
  if (renamed.empty()) return;
  for (Field& f : new_fields) {
    auto it = renamed.find(f.element);
    if (it == renamed.end()) continue;
    f.key = it->second + f.key.substr(f.element.size());
    f.element = it->second;
  }
}

}  // namespace

std::vector<ModelChange> diff_models(const Model& old_model, const Model& new_model, const ModelDiffOptions& options) {
  detail::FieldCollector a(old_model, options.derived);
  detail::FieldCollector b(new_model, options.derived);
  std::vector<ModelChange> out;
  // A model with no links is no model (git's side of an added or deleted file): its links are
  // all added or removed, and the whole-model fields would only repeat that.
  if (!old_model.links.empty() && !new_model.links.empty())
    diff_fields(a.model_fields(), b.model_fields(), "", options.tolerance, out);

  // Links pair by name; the k-th link of a name with the k-th of it on the other side, since
  // Choreonoid loads links without a name (the only name that can repeat).
  std::unordered_map<std::string_view, std::vector<std::size_t>> old_links;
  old_links.reserve(old_model.links.size());
  for (std::size_t i = 0; i < old_model.links.size(); ++i) old_links[old_model.links[i].name].push_back(i);
  std::unordered_map<std::string_view, std::size_t> seen;
  std::vector<bool> matched(old_model.links.size(), false);
  for (std::size_t i = 0; i < new_model.links.size(); ++i) {
    const std::size_t k = seen[new_model.links[i].name]++;
    auto it = old_links.find(new_model.links[i].name);
    if (it == old_links.end() || k >= it->second.size()) {
      const LinkFields l = b.link(i);
      ModelChange c;
      c.kind = ChangeKind::kAdded;
      c.link = l.name;
      c.field = "link";
      c.new_value = l.summary;
      c.new_source = l.source;
      out.push_back(std::move(c));
      continue;
    }
    const std::size_t j = it->second[k];
    matched[j] = true;
    const LinkFields before = a.link(j);
    LinkFields after = b.link(i);
    pair_shapes(before.fields, after.fields);
    diff_fields(before.fields, after.fields, new_model.links[i].name, options.tolerance, out);
  }
  for (std::size_t j = 0; j < old_model.links.size(); ++j) {
    if (matched[j]) continue;
    const LinkFields l = a.link(j);
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
  detail::FieldCollector fields(model, true);
  std::string out;
  for (const Field& f : fields.model_fields()) out += fmt::format("{}: {}\n", f.key, detail::field_value(f, kDigits));
  std::vector<std::size_t> order(model.links.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return model.links[x].name < model.links[y].name; });
  for (std::size_t i : order) {
    const LinkFields l = fields.link(i);
    out += fmt::format("\nlink '{}'\n", l.name);
    std::vector<const Field*> sorted;
    for (const Field& f : l.fields) sorted.push_back(&f);
    // Devices sorted by name; the link's own fields keep their fixed order.
    std::stable_sort(sorted.begin(), sorted.end(), [](const Field* x, const Field* y) {
      const bool dx = !x->element.empty() && x->element.rfind("device ", 0) == 0;
      const bool dy = !y->element.empty() && y->element.rfind("device ", 0) == 0;
      if (dx != dy) return dy;
      return dx && x->element < y->element;
    });
    for (const Field* f : sorted) out += fmt::format("  {}: {}\n", f->key, detail::field_value(*f, kDigits));
  }
  return out;
}

}  // namespace bodyfmt
