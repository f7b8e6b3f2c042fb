#pragma once
// The model's fields in one table, as MuJoCo keeps MJCF's attributes: for each field its name (as
// bodydiff prints it), how it is read from the model, its unit and how two values compare. One
// table per part of the model (the whole model, an extra joint, a link, a shape, a link's derived
// effects, a device); bodydiff, its canonical text and bodycheck --fix's proof that a rewrite
// changed nothing all read the fields through it (field_collector.h).

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::detail {

/// How a field's numbers are laid out (and shown, field_text.h).
enum class FieldStyle {
  kNumber,      // one number, or a list
  kVector,      // [x, y, z]
  kRange,       // [lower, upper]
  kAngleRange,  // [lower, upper] in radians, also shown in degrees
  kRotation,    // 3 zeros then a rotation matrix (9, row-major): rpy [..]
  kPose,        // translation (3) then rotation matrix (9, row-major): xyz [..] rpy [..]
  kAffine,      // translation (3) then a linear part that may scale: xyz [..] linear [..]
  kInertia,     // 3x3, shown as [xx, xy, xz, yy, yz, zz]
  kBox,         // min (3) then max (3): min [..] max [..]
  kText,        // text only
};

/// What a field's numbers measure, in the model's units (SI and radians).
enum class FieldUnit {
  kText,             // a name or a free string
  kEnum,             // one of a few words (joint type, geometry type, role)
  kInteger,          // an id or a count
  kFile,             // a mesh or texture file, compared by the key FileKeys gives it
  kLength,           // m
  kAngle,            // rad
  kRotation,         // a rotation matrix
  kPose,             // m and a rotation matrix
  kPlacement,        // m and a linear part that may scale (a shape's Transform)
  kDirection,        // an axis: compared as written (Choreonoid does not normalise it)
  kMass,             // kg
  kInertia,          // kg m^2, a tensor
  kRotorInertia,     // kg m^2 about the joint axis
  kJointPosition,    // rad for a revolute joint, m for a prismatic one
  kJointVelocity,    // rad/s or m/s
  kJointEffort,      // N m or N
  kForce,            // N
  kTorque,           // N m
  kAngularVelocity,  // rad/s
  kAcceleration,     // m/s^2
  kFrequency,        // Hz
  kColor,            // RGB in [0, 1]
  kDimensionless,    // a ratio, factor or exponent
  kGeometryData,     // every number of a mesh-like geometry: coordinates and indices
  kUnknown,          // the scalar key of a device no stage interprets
};

/// How two values of a field compare.
enum class FieldComparison {
  // Numbers within the tolerance: |a - b| <= tolerance * max(1, |a|, |b|) (relative above 1,
  // absolute below), text equal.
  kTolerance,
  // Every number and the text exactly: an id or a count names something, it measures nothing,
  // so 1000000000 and 1000000001 are two ids whatever the tolerance.
  kExact,
};

/// What the table says of one field.
struct FieldTraits {
  std::string_view name;  ///< after the element's key: "size" of "shape 2 size"; empty for the element itself
  FieldStyle style = FieldStyle::kText;
  FieldUnit unit = FieldUnit::kText;
  FieldComparison comparison = FieldComparison::kTolerance;
  bool derived = false;          ///< computed from other fields (total mass, world frames, boxes)
  bool geometry_detail = false;  ///< a size or file of a shape's geometry: meaningless once its type changed
};

/// One field's value, read from a model through the table.
struct Field {
  std::string key;  ///< as bodydiff prints it: "mass", "shape 2 size", "device 'gyro' id"
  const FieldTraits* traits = nullptr;
  FieldStyle style = FieldStyle::kText;  ///< the table's, unless the value says more (a revolute range)
  std::vector<double> numbers;
  std::string text;          ///< shown (kText), or shown before the numbers
  std::string compare_text;  ///< compared instead of `text` when set (a mesh file's key)
  SourceLocation source;
  // The shape, device or extra joint the field belongs to ("shape 2"); empty for the link's own
  // fields. An element's first field stands for it when the element is added or removed.
  std::string element;

  bool derived() const { return traits->derived; }
  bool geometry_detail() const { return traits->geometry_detail; }
};

/// Same values: the field's comparison (FieldComparison) within `tolerance`.
bool same_value(const Field& a, const Field& b, double tolerance);

/// |a - b| <= tolerance * max(1, |a|, |b|); NaN equals NaN, an infinity only itself.
bool same_number(double a, double b, double tolerance);

/// The key a mesh or texture file is compared by: its content (bodydiff: the same bytes under
/// another name are the same mesh; each file read once), or its URI and resolved path
/// (bodycheck --fix: a rewrite must name the same file).
class FileKeys {
 public:
  enum class By { kContent, kPath };
  explicit FileKeys(By by) : by_(by) {}
  std::string key(const std::string& uri, const std::string& resolved_path);

 private:
  By by_;
  std::map<std::string, std::string> cache_;
};

// What each table reads from.
struct ModelSubject {
  const Model& model;
  const Derived* derived;  ///< null: no derived fields
};
struct ExtraJointSubject {
  const Model& model;
  const ExtraJoint& joint;
};
struct LinkSubject {
  const Model& model;
  const Link& link;
  const MassProperties& mass;  ///< the link's mass, centre of mass and inertia combined
};
struct LinkDerivedSubject {
  Eigen::Isometry3d X_WL;
  const LinkBounds& bounds;
  SourceLocation at;  ///< the link's name, where derived effects are shown
};
struct ShapeSubject {
  const Shape& shape;
  FileKeys& files;
};
struct DeviceSubject {
  const Device& device;
};

/// One row of a table: the field, when a subject has it, and how to read it.
template <typename Subject>
struct FieldSpec {
  FieldTraits traits;
  bool (*present)(const Subject&);  ///< null: every subject has the field
  /// Sets the value, text and source of `field` (its key, traits and style are set).
  void (*read)(const Subject&, Field& field);
};

template <typename Subject>
using FieldTable = std::vector<FieldSpec<Subject>>;

const FieldTable<ModelSubject>& model_field_table();
const FieldTable<ExtraJointSubject>& extra_joint_field_table();
const FieldTable<LinkSubject>& link_field_table();
const FieldTable<ShapeSubject>& shape_field_table();
const FieldTable<LinkDerivedSubject>& link_derived_field_table();
const FieldTable<DeviceSubject>& device_field_table();
/// A device no stage interprets is compared by its scalar keys as written, under their
/// snake_case names: these two rows stand for each of them (numbers as numbers, the rest as text).
const FieldSpec<DeviceSubject>& device_key_number_spec();
const FieldSpec<DeviceSubject>& device_key_text_spec();

/// Appends the fields of `subject` that `table` holds, keyed "PREFIX NAME" (PREFIX alone for a
/// nameless row), each marked as part of `element`.
template <typename Subject>
void read_fields(const FieldTable<Subject>& table, const Subject& subject, const std::string& prefix,
                 const std::string& element, std::vector<Field>& out) {
  for (const FieldSpec<Subject>& spec : table) {
    if (spec.present && !spec.present(subject)) continue;
    Field f;
    f.key = prefix.empty()             ? std::string(spec.traits.name)
            : spec.traits.name.empty() ? prefix
                                       : prefix + " " + std::string(spec.traits.name);
    f.traits = &spec.traits;
    f.style = spec.traits.style;
    f.element = element;
    spec.read(subject, f);
    out.push_back(std::move(f));
  }
}

/// The scalar keys of a device no stage interprets (OpaqueParams), in name order.
void read_device_keys(const Device& device, const std::string& prefix, std::vector<Field>& out);

}  // namespace bodyfmt::detail
