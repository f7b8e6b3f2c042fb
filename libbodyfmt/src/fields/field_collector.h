#pragma once
// A model as lists of named fields, read through the field table (model_fields.h): the whole
// model's, then one list per link (its own fields, its shapes, its derived effects, its devices).
// What bodydiff compares and prints and what bodycheck --fix compares, so they cannot drift apart.

#include "fields/model_fields.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/model.h>

#include <string>
#include <utility>
#include <vector>

namespace bodyfmt::detail {

struct LinkFields {
  std::string name;
  std::string summary;  // "revolute joint under 'CHEST'", for an added or removed link
  SourceLocation source;
  std::vector<Field> fields;
};

// The fields of a model: the whole model's at once, a link's when asked for, so that comparing
// two models of 100,000 links holds the fields of one link pair at a time.
class FieldCollector {
 public:
  /// `derived`: also the derived effects (total mass, world frames, boxes). `files`: how mesh
  /// and texture files are compared.
  FieldCollector(const Model& model, bool derived, FileKeys::By files = FileKeys::By::kContent);
  const std::vector<Field>& model_fields() const { return model_fields_; }
  std::size_t link_count() const { return model_.links.size(); }
  LinkFields link(std::size_t i);

 private:
  const Model& model_;
  bool derived_;
  FileKeys files_;
  std::vector<Field> model_fields_;
  // libbodyfmt's derived data, as every tool computes it; only the masses without `derived`.
  Derived data_;
  std::vector<std::vector<std::pair<const Device*, std::string>>> devices_;  // per link, with their keys
};

}  // namespace bodyfmt::detail
