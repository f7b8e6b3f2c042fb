#include "fields/field_collector.h"

#include <fmt/format.h>

#include <map>

namespace bodyfmt::detail {

FieldCollector::FieldCollector(const Model& model, bool derived, FileKeys::By files)
    : model_(model), derived_(derived && !model.links.empty()), files_(files) {
  if (model.links.empty()) return;  // no model at all: a file that git adds or deletes
  if (derived_) {
    // Geometry and overflow problems are bodycheck's to report; a shape that cannot be
    // tessellated adds nothing to the boxes.
    struct Ignored : DiagnosticSink {
      void report(Diagnostic) override {}
    } ignored;
    data_ = compute_derived(model, ignored);
  } else {
    data_.mass.reserve(model.links.size());
    for (const Link& link : model.links) data_.mass.push_back(compute_mass_properties(link));
  }
  read_fields(model_field_table(), ModelSubject{model, derived_ ? &data_ : nullptr}, "", "", model_fields_);
  for (std::size_t i = 0; i < model.extra_joints.size(); ++i) {
    const std::string key = fmt::format("extra_joint {}", i);
    read_fields(extra_joint_field_table(), ExtraJointSubject{model, model.extra_joints[i]}, key, key, model_fields_);
  }
  // Devices under their link, by name (or type and rank when unnamed).
  devices_.resize(model.links.size());
  std::map<std::string, int> unnamed;
  for (const Device& d : model.devices) {
    if (d.link < 0 || d.link >= static_cast<LinkIndex>(model.links.size())) continue;
    devices_[d.link].emplace_back(&d, d.name.empty() ? fmt::format("device {}#{}", d.node_type, unnamed[d.node_type]++)
                                                     : "device '" + d.name + "'");
  }
}

LinkFields FieldCollector::link(std::size_t i) {
  const Link& link = model_.links[i];
  auto name = [&](LinkIndex j) { return j >= 0 ? model_.links[j].name : std::string(); };
  LinkFields lf;
  lf.name = link.name;
  lf.source = source_of(link, LinkSources::kName);
  lf.summary = link.parent >= 0
                   ? fmt::format("{} joint under '{}'", joint_type_name(link.joint_type), name(link.parent))
                   : fmt::format("root, {} joint", joint_type_name(link.joint_type));
  read_fields(link_field_table(), LinkSubject{model_, link, data_.mass[i]}, "", "", lf.fields);
  for (std::size_t s = 0; s < link.shapes.size(); ++s) {
    const std::string key = fmt::format("shape {}", s);
    read_fields(shape_field_table(), ShapeSubject{link.shapes[s], files_}, key, key, lf.fields);
  }
  if (derived_)
    read_fields(link_derived_field_table(), LinkDerivedSubject{as_isometry(data_.X_WL[i]), data_.bounds[i], lf.source},
                "", "", lf.fields);
  for (const auto& [device, key] : devices_[i]) {
    read_fields(device_field_table(), DeviceSubject{*device}, key, key, lf.fields);
    read_device_keys(*device, key, lf.fields);
  }
  return lf;
}

}  // namespace bodyfmt::detail
