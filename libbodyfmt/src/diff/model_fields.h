#pragma once
// A model as lists of named fields (the whole model, then one list per link): what bodydiff
// compares and what its canonical text prints, so that the two cannot drift apart.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <string>
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

struct ModelFields {
  std::vector<Field> model;       // name, total mass and centre of mass, extra joints
  std::vector<LinkFields> links;  // in the model's link order
};

ModelFields collect_fields(const Model& model, bool derived);

/// The value as shown: numbers shortest (`precision` 0) or rounded to `precision` digits.
std::string field_value(const Field& field, int precision = 0);

/// Same values within `tolerance` (relative above 1, absolute below).
bool same_value(const Field& a, const Field& b, double tolerance);

}  // namespace bodyfmt::detail
