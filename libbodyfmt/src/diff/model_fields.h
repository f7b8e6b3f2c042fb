#pragma once
// A model as lists of named fields (the whole model, then one list per link): what bodydiff
// compares and what its canonical text prints, so that the two cannot drift apart.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bodyfmt::detail {

enum class FieldStyle {
  kNumber,      // one number
  kVector,      // [x, y, z]
  kRange,       // [lower, upper]
  kAngleRange,  // [lower, upper] in radians, also shown in degrees
  kPose,        // translation (3) then rotation matrix (9, row-major): xyz [..] rpy [..]
  kAffine,      // translation (3) then a linear part that may scale: xyz [..] linear [..]
  kInertia,     // 3x3, shown as [xx, xy, xz, yy, yz, zz]
  kBox,         // min (3) then max (3): min [..] max [..]
  kText,        // text only
};

struct Field {
  std::string key;
  FieldStyle style = FieldStyle::kText;
  std::vector<double> numbers;
  std::string text;          // shown (kText), or shown before the numbers
  std::string compare_text;  // compared instead of `text` when set (a mesh file's content)
  SourceLocation source;
  bool derived = false;
  // The shape, device or extra joint the field belongs to ("shape 2"); empty for the link's own
  // fields. An element's first field stands for it when the element is added or removed.
  std::string element;
  // A size or file of a shape's geometry: meaningless once the geometry type itself changed.
  bool geometry_detail = false;
};

struct LinkFields {
  std::string name;
  std::string summary;  // "revolute joint under 'CHEST'", for an added or removed link
  SourceLocation source;
  std::vector<Field> fields;
};

// Mesh and texture files are compared by content: the same bytes under another name are the
// same mesh. Each file is read once.
class MeshContents {
 public:
  std::string content_key(const std::string& path);

 private:
  std::map<std::string, std::string> cache_;
};

// The fields of a model: the whole model's at once, a link's when asked for, so that comparing
// two models of 100,000 links holds the fields of one link pair at a time.
class FieldCollector {
 public:
  FieldCollector(const Model& model, bool derived);
  const std::vector<Field>& model_fields() const { return model_fields_; }
  std::size_t link_count() const { return model_.links.size(); }
  LinkFields link(std::size_t i);

 private:
  std::string link_name(LinkIndex i) const;

  const Model& model_;
  bool derived_;
  MeshContents meshes_;
  std::vector<Field> model_fields_;
  // libbodyfmt's derived data, as every tool computes it; only the masses without `derived`.
  Derived data_;
  std::vector<std::vector<std::pair<const Device*, std::string>>> devices_;  // per link, with their keys
};

/// The value as shown: numbers shortest (`precision` 0) or rounded to `precision` digits.
std::string field_value(const Field& field, int precision = 0);

/// Same values within `tolerance` (relative above 1, absolute below).
bool same_value(const Field& a, const Field& b, double tolerance);

}  // namespace bodyfmt::detail
