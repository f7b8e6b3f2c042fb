// The fix-its of `bodycheck --fix=geometry` (issue 39): a link's centre of mass and inertia
// replaced, number by number where they are written, by those computed from its shapes.

#include <bodyfmt/geometry_fix.h>
#include <bodyfmt/inertia.h>

#include "yaml/yaml_node.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <tuple>

namespace bodyfmt {
namespace {

// Zeroing what is rounding: the off-diagonal entries of a symmetric shape come out ~1e-17.
double cleaned(double v, double scale) { return std::abs(v) <= 1e-12 * scale ? 0.0 : v; }

std::string number_text(double v, int digits) {
  if (v == 0) return "0";
  return fmt::format("{:.{}g}", v, digits);
}

double read_back(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

struct Written {
  MassProperties keys;
  int digits = 9;
};

Written written_form(const MassProperties& keys) {
  const double scale = keys.inertia.cwiseAbs().maxCoeff();
  Written w;
  for (int digits : {9, 17}) {
    w.digits = digits;
    w.keys = keys;
    for (int i = 0; i < 3; ++i) {
      // A picometre is rounding at any robot's scale.
      const double c = keys.center_of_mass[i];
      w.keys.center_of_mass[i] = read_back(number_text(std::abs(c) < 1e-12 ? 0.0 : c, digits));
      for (int j = 0; j < 3; ++j)
        w.keys.inertia(i, j) = read_back(number_text(cleaned(keys.inertia(i, j), scale), digits));
    }
    if (inertia_validity(principal_inertia(w.keys.inertia)).valid()) break;
  }
  return w;
}

/// The mapping that holds the link's keys: the one whose `key` value is written at `at`.
struct Found {
  const yaml::Node* mapping = nullptr;
};

void find_mapping(const yaml::NodeRef& ref, const std::string& key, const SourceLocation& at,
                  std::set<const yaml::Node*>& seen, Found& found) {
  if (!ref || found.mapping || !seen.insert(ref.node).second) return;
  if (ref->is_mapping()) {
    for (const yaml::MapEntry& e : ref->entries()) {
      if (e.key == key && e.value && !e.merged && e.value.alias_site == nullptr && e.value->location == at) {
        found.mapping = ref.node;
        return;
      }
      find_mapping(e.value, key, at, seen, found);
    }
  } else if (ref->is_sequence()) {
    for (const yaml::NodeRef& item : ref->items()) find_mapping(item, key, at, seen, found);
  }
}

std::optional<FixIt> replace_scalar(const yaml::NodeRef& item, const std::string& file, std::string_view text,
                                    std::string replacement) {
  if (!item || !item->is_scalar() || item.alias_site != nullptr || !item->span.editable() ||
      item->span.end > text.size())
    return std::nullopt;
  FixIt f;
  f.file = FileName(file);
  f.begin = item->span.begin;
  f.end = item->span.end;
  f.line = item->location.line;
  f.column = item->span.column;
  f.original = std::string(text.substr(f.begin, f.end - f.begin));
  f.replacement = std::move(replacement);
  f.safety = FixSafety::kUnsafe;
  return f;
}

/// Replaces each number of a sequence value; false when one is not a plain number in place.
bool replace_numbers(const yaml::MapEntry& entry, const std::vector<std::string>& numbers, const std::string& file,
                     std::string_view text, std::vector<FixIt>& fixes) {
  if (entry.merged || entry.value.alias_site != nullptr || !entry.value->is_sequence()) return false;
  const auto items = entry.value->items();
  if (items.size() != numbers.size()) return false;
  std::size_t k = 0;
  for (const yaml::NodeRef& item : items) {
    auto f = replace_scalar(item, file, text, numbers[k++]);
    if (!f) return false;
    if (f->replacement != f->original) fixes.push_back(std::move(*f));
  }
  return true;
}

/// A new `key: value` line before the entry `before`, indented as it is.
std::optional<FixIt> insert_before(const yaml::MapEntry& before, const std::string& line, const std::string& file,
                                   std::string_view text) {
  if (before.merged || !before.key_span.editable() || before.key_span.begin > text.size()) return std::nullopt;
  const std::size_t at = before.key_span.begin;
  const std::size_t line_start =
      text.rfind('\n', at == 0 ? 0 : at - 1) == std::string_view::npos ? 0 : text.rfind('\n', at == 0 ? 0 : at - 1) + 1;
  // Only a block mapping's key starts its line (after the indentation and a sequence's "- ").
  for (std::size_t i = line_start; i < at; ++i)
    if (text[i] != ' ' && text[i] != '-') return std::nullopt;
  FixIt f;
  f.file = FileName(file);
  f.begin = f.end = at;
  f.line = before.key_location.line;
  f.column = before.key_location.column;
  f.replacement = line + "\n" + std::string(at - line_start, ' ');
  f.safety = FixSafety::kUnsafe;
  return f;
}

}  // namespace

MassProperties written_mass_keys(const MassProperties& keys) { return written_form(keys).keys; }

namespace {

/// The fix-its that write `keys` over the `center_of_mass` and `inertia` entries of `mapping`
/// (inserting a missing one before its `mass` entry); `owner` names it in `why`.
std::vector<FixIt> mass_key_fixes(std::string_view text, const std::string& file, const yaml::Node& mapping,
                                  const std::string& owner, const MassProperties& keys, std::string& why) {
  const Written w = written_form(keys);
  const auto n = [&](double v) { return number_text(v, w.digits); };
  const Eigen::Matrix3d& I = w.keys.inertia;
  const Eigen::Vector3d& c = w.keys.center_of_mass;
  const std::vector<std::string> com_numbers = {n(c.x()), n(c.y()), n(c.z())};
  const std::vector<std::string> nine = {n(I(0, 0)), n(I(0, 1)), n(I(0, 2)), n(I(1, 0)), n(I(1, 1)),
                                         n(I(1, 2)), n(I(2, 0)), n(I(2, 1)), n(I(2, 2))};
  const std::vector<std::string> six = {n(I(0, 0)), n(I(0, 1)), n(I(0, 2)), n(I(1, 1)), n(I(1, 2)), n(I(2, 2))};
  const auto flow = [](const std::vector<std::string>& v) { return "[" + fmt::format("{}", fmt::join(v, ", ")) + "]"; };

  const yaml::MapEntry* mass = mapping.find("mass");
  const yaml::MapEntry* inertia = mapping.find("inertia");
  const yaml::MapEntry* com = mapping.find("center_of_mass");
  if (!com) com = mapping.find("centerOfMass");
  std::vector<FixIt> fixes;
  const auto fail = [&](const std::string& what) {
    why = fmt::format("the {} of {} is not written as plain numbers in place", what, owner);
    fixes.clear();
    return fixes;
  };
  if (!mass) return fail("mass key");
  // Missing keys go in as one insertion (two at one place would overlap).
  std::vector<std::string> inserted;
  if (inertia) {
    const std::size_t count = inertia->value && inertia->value->is_sequence() ? inertia->value->items().size() : 0;
    if (!replace_numbers(*inertia, count == 6 ? six : nine, file, text, fixes)) return fail("inertia");
  } else {
    inserted.push_back("inertia: " + flow(nine));
  }
  if (com) {
    if (!replace_numbers(*com, com_numbers, file, text, fixes)) return fail("center_of_mass");
  } else if (!c.isZero(0)) {
    inserted.push_back("center_of_mass: " + flow(com_numbers));
  }
  if (!inserted.empty()) {
    const std::string indentation(static_cast<std::size_t>(std::max(0, mass->key_location.column - 1)), ' ');
    auto f = insert_before(*mass, fmt::format("{}", fmt::join(inserted, "\n" + indentation)), file, text);
    if (!f) return fail("mass key");
    fixes.push_back(std::move(*f));
  }
  return fixes;
}

/// The mapping written at `at` (a RigidBody element as the loader located it), not reached
/// through an alias.
void find_node(const yaml::NodeRef& ref, const SourceLocation& at, std::set<const yaml::Node*>& seen,
               const yaml::Node*& found) {
  if (!ref || found || !seen.insert(ref.node).second) return;
  if (ref->is_mapping()) {
    if (ref.alias_site == nullptr && ref->location == at) {
      found = ref.node;
      return;
    }
    for (const yaml::MapEntry& e : ref->entries())
      if (!e.merged) find_node(e.value, at, seen, found);
  } else if (ref->is_sequence()) {
    for (const yaml::NodeRef& item : ref->items()) find_node(item, at, seen, found);
  }
}

}  // namespace

std::vector<FixIt> link_mass_fixes(std::string_view text, const std::string& file, const Link& link,
                                   const MassProperties& keys, std::string& why) {
  const SourceLocation mass_at = link.sources.mass();
  if (!mass_at.known()) {
    why = fmt::format("link \"{}\" has no link-level mass key to scale its geometry to", link.name);
    return {};
  }
  CollectingSink ignored;  // the file loaded before; its YAML findings are the loader's
  const std::unique_ptr<yaml::Document> doc = yaml::parse_yaml(text, file, yaml::ParseOptions{}, ignored);
  Found found;
  std::set<const yaml::Node*> seen;
  if (doc) find_mapping(doc->root, "mass", mass_at, seen, found);
  if (!found.mapping) {
    why = fmt::format("the mass of link \"{}\" is not written in place in {} (an alias or merge key)", link.name, file);
    return {};
  }
  return mass_key_fixes(text, file, *found.mapping, fmt::format("link \"{}\"", link.name), keys, why);
}

std::vector<FixIt> rigid_body_mass_fixes(std::string_view text, const std::string& file, const Link& link,
                                         std::size_t contribution, const MassProperties& keys, std::string& why) {
  const SourceLocation at =
      contribution < link.mass_contributions.size() ? link.mass_contributions[contribution].source : SourceLocation{};
  const std::string owner = fmt::format("the RigidBody element of link \"{}\" at line {}", link.name, at.line);
  CollectingSink ignored;
  const std::unique_ptr<yaml::Document> doc =
      at.known() ? yaml::parse_yaml(text, file, yaml::ParseOptions{}, ignored) : nullptr;
  const yaml::Node* mapping = nullptr;
  std::set<const yaml::Node*> seen;
  if (doc) find_node(doc->root, at, seen, mapping);
  if (!mapping) {
    why = fmt::format("{} is not written in place in {} (an alias or merge key)", owner, file);
    return {};
  }
  return mass_key_fixes(text, file, *mapping, owner, keys, why);
}

std::vector<bool> links_for_geometry_fix(const Model& model, const std::vector<Diagnostic>& findings) {
  // A set of the places the rules reported at, so that a model whose every link is flagged
  // (10,000 links in bodyview) is not searched once per finding.
  std::set<std::tuple<std::string, int, int>> at;
  for (const Diagnostic& d : findings) {
    if ((d.rule_id == "inertia-implausible" || d.rule_id == "inertia-triangle" ||
         d.rule_id == "inertia-not-positive-definite" || d.rule_id == "inertia-com-outside") &&
        d.location.known())
      at.emplace(d.location.file.str(), d.location.line, d.location.column);
  }
  const auto reported = [&](const SourceLocation& l) {
    return l.known() && at.count({l.file.str(), l.line, l.column}) > 0;
  };
  std::vector<bool> flagged(model.links.size(), false);
  for (std::size_t i = 0; i < model.links.size() && !at.empty(); ++i) {
    const Link& link = model.links[i];
    bool hit = reported(link.source) || reported(link.sources.inertia()) || reported(link.sources.mass()) ||
               reported(link.sources.center_of_mass());
    for (const MassContribution& c : link.mass_contributions) hit = hit || reported(c.source);
    flagged[i] = hit;
  }
  return flagged;
}

}  // namespace bodyfmt
