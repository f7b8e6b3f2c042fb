#pragma once
/// The in-memory Body model: what the loader produces and every later stage reads.
///
/// All values are SI (metres, kilograms, seconds) and radians; degrees exist only in the file
/// and are converted by the loader. Elements refer to each other by index, never by pointer.
/// Every element keeps the source location of the text that defined it.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/mesh.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

using LinkIndex = int;  ///< index into Model::links; -1 = none
using MeshIndex = int;  ///< index into Model::meshes; -1 = not loaded

constexpr double kUnlimited = std::numeric_limits<double>::max();

// ---------------------------------------------------------------------------------------
// Geometry (body-format-spec §9). Cylinder, Cone and Capsule run along the local +Y axis.

struct Box {
  Eigen::Vector3d size{1, 1, 1};  ///< full edge lengths
};
struct Sphere {
  double radius = 1;
};
struct Cylinder {
  double radius = 1;
  double height = 1;
  bool top = true;
  bool bottom = true;
};
struct Cone {
  double radius = 1;
  double height = 1;
  bool bottom = true;
};
struct Capsule {
  double radius = 1;
  double height = 1;  ///< cylindrical part only; total length = height + 2 radius
};
/// VRML97 Extrusion: cross-section in the local XZ plane swept along the spine.
struct Extrusion {
  std::vector<Eigen::Vector2d> cross_section;
  std::vector<Eigen::Vector3d> spine;
  /// 1 entry or one per spine point; each axis as written (not normalised, may be zero).
  std::vector<Eigen::AngleAxisd> orientation;
  std::vector<Eigen::Vector2d> scale;  ///< 1 entry or one per spine point
  double crease_angle = 0;
  bool begin_cap = true;
  bool end_cap = true;
};
/// VRML97 ElevationGrid: vertex (i, j) at (i x_spacing, height[j x_dim + i], j z_spacing).
struct ElevationGrid {
  int x_dimension = 0;
  int z_dimension = 0;
  double x_spacing = 1;
  double z_spacing = 1;
  std::vector<double> height;
  bool ccw = true;
  double crease_angle = 0;
};
/// Polygons as VRML97 coordIndex: each polygon terminated by -1.
struct IndexedFaceSet {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> faces;
  std::vector<Eigen::Vector2d> tex_coords;
  std::vector<int> tex_coord_indices;
  double crease_angle = 0;
};
/// Flat list of triangles (3 indices each), the form Choreonoid's writer emits.
struct TriangleMeshGeometry {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> faces;
  std::vector<Eigen::Vector2d> tex_coords;
  std::vector<int> tex_coord_indices;
  double crease_angle = 0;
};
/// An external mesh file (geometry `type: Resource`, or a Resource element's mesh part).
struct MeshResource {
  std::string uri;            ///< as written
  std::string resolved_path;  ///< empty when it could not be resolved
  std::string node;           ///< `node`/`fragment`: named part of the file; empty = whole file
  double length_scale = 1.0;  ///< metadata length_unit: 0.001 for millimeter, 0.0254 for inch
  bool y_up = false;          ///< metadata upper_axis: Y
  std::optional<double> crease_angle;
  MeshIndex mesh = -1;        ///< Model::meshes entry once imported
  SourceLocation uri_source;  ///< the `uri:` value, where problems with the file are reported
};

/// A value kept on the heap and copied deeply. Reads as the value it holds (a moved-from
/// HeapValue holds nothing and may only be assigned or destroyed).
template <typename T>
class HeapValue {
 public:
  HeapValue() : value_(std::make_unique<T>()) {}
  HeapValue(T value) : value_(std::make_unique<T>(std::move(value))) {}  // NOLINT: implicit, as the value
  HeapValue(const HeapValue& other) : value_(std::make_unique<T>(*other)) {}
  HeapValue(HeapValue&&) noexcept = default;
  HeapValue& operator=(const HeapValue& other) { return *this = *other; }
  HeapValue& operator=(HeapValue&&) noexcept = default;
  HeapValue& operator=(T value) {
    value_ = std::make_unique<T>(std::move(value));
    return *this;
  }

  operator const T&() const { return *value_; }  // NOLINT: reads as the value
  const T& operator*() const { return *value_; }
  T& operator*() { return *value_; }
  const T* operator->() const { return value_.get(); }
  T* operator->() { return value_.get(); }

 private:
  std::unique_ptr<T> value_;
};

/// The geometry of a shape. The alternatives that hold vectors or strings are kept in a HeapValue, so that
/// the variant is sized by the primitives (32 bytes instead of 160): a model of 100,000 box
/// shapes does not carry room for a mesh resource in each. Read them with geometry_if and
/// geometry_get; the primitives also with std::get_if and std::get.
using Geometry = std::variant<Box, Sphere, Cylinder, Cone, Capsule, HeapValue<Extrusion>, HeapValue<ElevationGrid>,
                              HeapValue<IndexedFaceSet>, HeapValue<TriangleMeshGeometry>, HeapValue<MeshResource>>;

namespace detail {
template <typename T, typename Variant>
struct IsAlternative;
template <typename T, typename... Ts>
struct IsAlternative<T, std::variant<Ts...>> : std::bool_constant<(std::is_same_v<T, Ts> || ...)> {};
template <typename T>
struct IsHeapValue : std::false_type {};
template <typename T>
struct IsHeapValue<HeapValue<T>> : std::true_type {};
/// How a geometry type is stored in Geometry: itself (the primitives) or in a HeapValue.
template <typename T>
struct GeometryStorage {
  static_assert(!IsHeapValue<T>::value, "name the geometry type, not its storage");
  using type = std::conditional_t<IsAlternative<T, Geometry>::value, T, HeapValue<T>>;
  static_assert(IsAlternative<type, Geometry>::value, "name a geometry type (Box, ..., MeshResource)");
};
}  // namespace detail

/// The geometry as a T (Box, ..., MeshResource), or nullptr when it holds another type.
template <typename T>
const T* geometry_if(const Geometry& geometry) {
  const auto* stored = std::get_if<typename detail::GeometryStorage<T>::type>(&geometry);
  if constexpr (std::is_same_v<T, typename detail::GeometryStorage<T>::type>)
    return stored;
  else
    return stored ? &**stored : nullptr;
}
template <typename T>
T* geometry_if(Geometry& geometry) {
  return const_cast<T*>(geometry_if<T>(static_cast<const Geometry&>(geometry)));
}
/// The geometry as a T; throws std::bad_variant_access when it holds another type.
template <typename T>
const T& geometry_get(const Geometry& geometry) {
  return std::get<typename detail::GeometryStorage<T>::type>(geometry);
}
template <typename T>
bool geometry_is(const Geometry& geometry) {
  return std::holds_alternative<typename detail::GeometryStorage<T>::type>(geometry);
}
/// A geometry alternative as its geometry type (for std::visit over a Geometry).
template <typename T>
const T& geometry_value(const T& value) {
  return value;
}
template <typename T>
const T& geometry_value(const HeapValue<T>& value) {
  return *value;
}

std::string_view geometry_type_name(const Geometry& geometry);

struct Texture {
  std::string uri;
  std::string resolved_path;
  bool repeat_s = true;
  bool repeat_t = true;
};

/// An optional value kept on the heap: one pointer while empty. For members that most
/// elements leave out (a shape's material is 104 bytes, its texture 72), so that a model of
/// many plain shapes does not carry them inline. Reads as the std::optional it holds.
template <typename T>
class HeapOptional {
 public:
  HeapOptional() = default;
  HeapOptional(std::nullopt_t) {}  // NOLINT: implicit, as std::optional
  HeapOptional(const T& value) : value_(std::make_unique<std::optional<T>>(value)) {}  // NOLINT
  HeapOptional(const std::optional<T>& value) { *this = value; }                       // NOLINT
  HeapOptional(const HeapOptional& other) { *this = other; }
  HeapOptional(HeapOptional&&) noexcept = default;
  HeapOptional& operator=(const HeapOptional& other) { return *this = other.get(); }
  HeapOptional& operator=(HeapOptional&&) noexcept = default;
  HeapOptional& operator=(const std::optional<T>& value) {
    if (!value)
      value_.reset();
    else if (value_)
      **value_ = *value;
    else
      value_ = std::make_unique<std::optional<T>>(value);
    return *this;
  }
  HeapOptional& operator=(const T& value) { return *this = std::optional<T>(value); }
  HeapOptional& operator=(std::nullopt_t) {
    value_.reset();
    return *this;
  }

  const std::optional<T>& get() const { return value_ ? *value_ : empty(); }
  operator const std::optional<T>&() const { return get(); }  // NOLINT: reads as the optional
  explicit operator bool() const { return value_ != nullptr; }
  bool has_value() const { return value_ != nullptr; }
  const T& operator*() const { return **value_; }
  T& operator*() { return **value_; }
  const T* operator->() const { return &**value_; }
  T* operator->() { return &**value_; }
  const T& value() const { return get().value(); }
  template <typename U>
  T value_or(U&& fallback) const {
    return get().value_or(std::forward<U>(fallback));
  }
  T& emplace() {
    value_ = std::make_unique<std::optional<T>>(T{});
    return **value_;
  }
  void reset() { value_.reset(); }

 private:
  static const std::optional<T>& empty() {
    static const std::optional<T> none;
    return none;
  }
  std::unique_ptr<std::optional<T>> value_;  ///< never holds an empty optional
};

/// A string kept on the heap: one pointer while empty. For names and modes that most elements
/// leave out (a link's joint_name, actuation_mode, contact_material), so that a model of
/// 100,000 links does not carry three 32-byte strings per link. Reads as the std::string it
/// holds.
class HeapString {
 public:
  HeapString() = default;
  HeapString(std::string_view value) { *this = value; }                          // NOLINT: implicit, as std::string
  HeapString(const std::string& value) : HeapString(std::string_view(value)) {}  // NOLINT
  HeapString(const char* value) : HeapString(std::string_view(value)) {}         // NOLINT
  HeapString(const HeapString& other) : HeapString(other.view()) {}
  HeapString(HeapString&&) noexcept = default;
  HeapString& operator=(const HeapString& other) { return *this = other.view(); }
  HeapString& operator=(HeapString&&) noexcept = default;
  HeapString& operator=(std::string_view value) {
    if (value.empty())
      value_.reset();
    else if (value_)
      value_->assign(value);
    else
      value_ = std::make_unique<std::string>(value);
    return *this;
  }
  HeapString& operator=(const std::string& value) { return *this = std::string_view(value); }
  HeapString& operator=(const char* value) { return *this = std::string_view(value); }

  const std::string& str() const { return value_ ? *value_ : empty_string(); }
  std::string_view view() const { return str(); }
  operator const std::string&() const { return str(); }  // NOLINT: reads as a string
  operator std::string_view() const { return str(); }    // NOLINT
  bool empty() const { return value_ == nullptr; }

  friend bool operator==(const HeapString& a, std::string_view b) { return a.view() == b; }
  friend bool operator==(std::string_view a, const HeapString& b) { return a == b.view(); }
  friend bool operator!=(const HeapString& a, std::string_view b) { return a.view() != b; }
  friend bool operator!=(std::string_view a, const HeapString& b) { return a != b.view(); }
  friend std::string operator+(std::string_view a, const HeapString& b) { return std::string(a) += b.str(); }
  friend std::string operator+(const HeapString& a, std::string_view b) { return std::string(a.str()).append(b); }

 private:
  static const std::string& empty_string() {
    static const std::string none;
    return none;
  }
  std::unique_ptr<std::string> value_;  ///< never holds an empty string
};

struct Appearance {
  HeapOptional<Material> material;
  HeapOptional<Texture> texture;
};

// Shapes and scene frames keep their affine transforms as the top 3x4 block
// (Eigen::AffineCompact3d): the bottom row is always [0 0 0 1], and a large model holds two
// per link. They convert to and multiply with Eigen::Affine3d exactly (Eigen combines the
// linear and translation parts alike for both storages).

/// A transform node of a link's element tree (Transform, RigidBody, Visual, Collision,
/// device, Resource, or a Shape's own transform). Kept so that consumers can rebuild the
/// hierarchy: Choreonoid's bounding boxes and a glTF node tree depend on it.
struct SceneFrame {
  int parent = -1;  ///< index into Link::frames; -1 = the link frame
  /// The Link::mass_contributions entry of the RigidBody element whose frame this is, or -1:
  /// the shapes below a RigidBody are the body whose mass data it writes.
  int rigid_body = -1;
  Eigen::AffineCompact3d X_PF = Eigen::AffineCompact3d::Identity();  ///< in the parent frame; may scale
};

/// A shape placed in its link's frame.
struct Shape {
  HeapString name;
  Geometry geometry;
  Appearance appearance;
  Eigen::AffineCompact3d X_LS = Eigen::AffineCompact3d::Identity();  ///< may contain scale
  int frame = -1;            ///< innermost Link::frames entry enclosing the shape; X_LS is its pose
  int division_number = 20;  ///< tessellation (values < 4 mean the default, 20)
  bool visual = true;        ///< part of the visual model
  bool collision = true;     ///< part of the collision model
  SourceLocation source;
};

// ---------------------------------------------------------------------------------------
// Mass

/// A rigid-body contribution in the link frame: mass, centre of mass, inertia about the
/// centre of mass in link axes. Combined per link by compute_mass_properties().
struct MassContribution {
  double mass = 0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  bool from_link_keys = false;  ///< link-level mass/center_of_mass/inertia keys
  /// The loader refused the inertia as written (load-inertia-size, a bad number): what stands
  /// in its place is no one's tensor, and no rule judges it.
  bool inertia_refused = false;
  SourceLocation source;
};

/// Mass, centre of mass (link frame) and inertia about it (link axes). Default-constructed,
/// it holds Choreonoid's defaults for a link without mass data (body-format-spec §6.4 rule 4:
/// 1 kg at the origin with identity inertia); this is the one place they are written.
struct MassProperties {
  double mass = 1.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();
};

// ---------------------------------------------------------------------------------------
// Links and joints

enum class JointType { kFree, kFixed, kRevolute, kPrismatic, kPseudoContinuousTrack };

std::string_view joint_type_name(JointType type);

/// Where the fields that rules and writers point at were written. A link's keys are written
/// in one file, so each field keeps its line and column and the link one file name (8 bytes a
/// field instead of a whole SourceLocation); the rare field written in another file (a
/// SubBody node overriding its root's pose or joint) keeps its file on the side.
class LinkSources {
 public:
  enum Field {
    kName,
    kParent,
    kTranslation,
    kRotation,
    kJointType,
    kJointAxis,
    kJointId,
    kJointRange,
    kJointVelocity,
    kMass,
    kCenterOfMass,
    kInertia,
    kFieldCount
  };

  LinkSources() = default;
  LinkSources(const LinkSources& other);
  LinkSources(LinkSources&&) noexcept = default;
  LinkSources& operator=(const LinkSources& other);
  LinkSources& operator=(LinkSources&&) noexcept = default;

  SourceLocation get(Field field) const;
  void set(Field field, const SourceLocation& at);

  SourceLocation name() const { return get(kName); }
  SourceLocation parent() const { return get(kParent); }
  SourceLocation translation() const { return get(kTranslation); }
  SourceLocation rotation() const { return get(kRotation); }
  SourceLocation joint_type() const { return get(kJointType); }
  SourceLocation joint_axis() const { return get(kJointAxis); }
  SourceLocation joint_id() const { return get(kJointId); }
  SourceLocation joint_range() const { return get(kJointRange); }
  SourceLocation joint_velocity() const { return get(kJointVelocity); }
  SourceLocation mass() const { return get(kMass); }
  SourceLocation center_of_mass() const { return get(kCenterOfMass); }
  SourceLocation inertia() const { return get(kInertia); }

 private:
  struct Position {
    int line = 0;
    int column = 0;
  };
  std::unique_ptr<FileName[]> other_files_;  ///< per field, for those not in in_file_; null until needed
  FileName file_;                            ///< the file of the fields in in_file_
  std::uint16_t in_file_ = 0;                ///< bit per field: written in file_
  Position at_[kFieldCount];
  static_assert(kFieldCount <= 16);
};

struct Link {
  std::string name;
  HeapString joint_name;
  SourceLocation source;  // up here and joint_id beside joint_type: no padding before X_PL (16-byte aligned)
  LinkIndex parent = -1;
  std::vector<LinkIndex> children;

  /// Offset of this link (= its joint frame) in the parent link frame; for the root, its
  /// initial pose in the world. A rigid transform, kept in the 3x4 storage of shapes and
  /// frames (products with transforms are exact; with a point, use as_isometry(X_PL)).
  Eigen::AffineCompact3d X_PL = Eigen::AffineCompact3d::Identity();

  JointType joint_type = JointType::kFixed;
  int joint_id = -1;
  Eigen::Vector3d joint_axis{0, 0, 1};  ///< link frame; not normalised (Choreonoid does not)
  double joint_range_lower = -kUnlimited;
  double joint_range_upper = kUnlimited;
  double velocity_lower = -kUnlimited;
  double velocity_upper = kUnlimited;
  double effort_lower = -kUnlimited;
  double effort_upper = kUnlimited;
  double initial_displacement = 0;
  double joint_axis_inertia = 0;  ///< equivalent rotor inertia
  HeapString actuation_mode;
  HeapString contact_material;

  std::vector<MassContribution> mass_contributions;
  std::vector<Shape> shapes;
  std::vector<SceneFrame> frames;  ///< parents come before their children

  LinkSources sources;
};

/// Revolute or prismatic: a joint with one coordinate, whose axis and range mean something.
bool is_one_dof(const Link& link);

/// A 3x4 transform (Link::X_PL, Derived::X_WL) as the isometry to multiply points with: the
/// 3x4 and 4x4 storages round a transform-point product differently, and this keeps the
/// values the tools gave before links kept their frames in 3x4.
inline Eigen::Isometry3d as_isometry(const Eigen::AffineCompact3d& X) { return Eigen::Isometry3d(X.matrix()); }
/// Where `field` of `link` was written, or the link's own location when it was not.
SourceLocation source_of(const Link& link, LinkSources::Field field);
/// The first RigidBody node that gives `link` mass (not its link-level keys); unknown if none.
SourceLocation rigid_body_source(const Link& link);
/// The most specific place the link's inertia is written: its inertia key, its first RigidBody,
/// its mass key, else the link itself.
SourceLocation inertia_source(const Link& link);

// ---------------------------------------------------------------------------------------
// Devices (body-format-spec §10)

struct CameraParams {
  std::string format;  ///< COLOR, DEPTH, COLOR_DEPTH, POINT_CLOUD, COLOR_POINT_CLOUD
  std::string lens_type = "NORMAL";
  int width = 640;
  int height = 480;
  double field_of_view = 0.785398;
  double near_clip_distance = 0.04;
  double far_clip_distance = 200;
  double frame_rate = 30;
  std::string optical_frame = "gl";
  /// `optical_frame_rotation`, post-multiplied onto the optical frame (body-format-spec §10.3).
  Eigen::Matrix3d optical_frame_rotation = Eigen::Matrix3d::Identity();
  // RangeCamera only
  double min_distance = 0.1;
  double max_distance = 10;
  double detection_rate = 1.0;
  double error_deviation = 0;
};
struct RangeSensorParams {
  double yaw_range = 2.0943951023931953;  // 120 deg
  double yaw_step = 1.0;                  // Choreonoid's constructor default is 1 radian
  double pitch_range = 0;
  double pitch_step = 1.0;
  double min_distance = 0.1;
  double max_distance = 10;
  double scan_rate = 10;
  double detection_rate = 1.0;
  double error_deviation = 0;
};
struct LightParams {
  Eigen::Vector3d color{1, 1, 1};
  double intensity = 1;
  Eigen::Vector3d attenuation{1, 0, 0};
  // SpotLight only
  Eigen::Vector3d direction{0, 0, -1};
  double beam_width = 1.5707963267948966;
  double cut_off_angle = 0.7853981633974483;
  double cut_off_exponent = 1;
};
struct ForceSensorParams {
  Eigen::Vector3d max_force = Eigen::Vector3d::Constant(kUnlimited);
  Eigen::Vector3d max_torque = Eigen::Vector3d::Constant(kUnlimited);
};
struct InertialSensorParams {  ///< RateGyroSensor, AccelerationSensor, IMU
  Eigen::Vector3d max_angular_velocity = Eigen::Vector3d::Constant(kUnlimited);
  Eigen::Vector3d max_acceleration = Eigen::Vector3d::Constant(kUnlimited);
};
/// Devices whose parameters no stage interprets yet (Holder, Attachment, Conveyor, DigitalIO,
/// MarkerDevice, ZmpDevice) and plugin devices: kept as their scalar keys.
struct OpaqueParams {};

using DeviceParams =
    std::variant<OpaqueParams, CameraParams, RangeSensorParams, LightParams, ForceSensorParams, InertialSensorParams>;

struct Device {
  std::string node_type;  ///< as written, e.g. "Camera", "IMU", "AGXVehicleContinuousTrackDevice"
  std::string type;       ///< Choreonoid's device class, e.g. "RangeCamera", "Imu", "HolderDevice"
  std::string name;
  int id = -1;
  bool on = true;
  bool plugin = false;  ///< a plugin node type Choreonoid loads only with its plugin
  LinkIndex link = -1;
  Eigen::Isometry3d X_LD = Eigen::Isometry3d::Identity();
  DeviceParams params;
  /// Every scalar key of the node as written (for opaque devices and exporters' comments).
  std::map<std::string, std::string> keys;
  /// Where the value of every key of the node is written, under the key as written (either
  /// spelling), so that a finding about one parameter points at it.
  std::map<std::string, SourceLocation, std::less<>> key_sources;
  SourceLocation source;

  /// The location of the first of `spellings` that the node has, else `source`.
  const SourceLocation& key_source(std::initializer_list<std::string_view> spellings) const {
    for (std::string_view key : spellings)
      if (auto it = key_sources.find(key); it != key_sources.end() && it->second.known()) return it->second;
    return source;
  }
};

// ---------------------------------------------------------------------------------------
// Extra joints (closed loops, body-format-spec §12)

struct ExtraJoint {
  std::string type;  ///< fixed, hinge, ball, piston
  LinkIndex link1 = -1;
  LinkIndex link2 = -1;
  Eigen::Vector3d axis{1, 0, 0};
  Eigen::Isometry3d X_1J = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_2J = Eigen::Isometry3d::Identity();
  SourceLocation source;
};

// ---------------------------------------------------------------------------------------
// Imported meshes, shared between shapes that reference the same (file, node, metadata).

struct MeshPart {
  TriangleMesh mesh;  ///< in the resource frame, metres, Z-up after metadata is applied
  std::optional<Material> material;
  std::optional<Texture> texture;
};

struct MeshAsset {
  std::string path;
  std::string node;
  std::vector<MeshPart> parts;
  /// The box Choreonoid's scene graph reports for this asset in the resource frame: group
  /// boxes are unions of their children, transform boxes are the axis-aligned box of the
  /// transformed child box (8 corners), so nested rotations inflate it (used to compare with
  /// Choreonoid's reference boxes; the tight box is bounding_box of the parts).
  BoundingBox scene_bounds;
};

// ---------------------------------------------------------------------------------------

struct Model {
  std::string name;
  std::string source_file;
  double format_version = 0;
  bool angles_in_degrees = true;
  /// Links in Choreonoid's order: depth-first pre-order from the root; links[0] is the root.
  std::vector<Link> links;
  /// Sorted by link order, then file order.
  std::vector<Device> devices;
  std::vector<ExtraJoint> extra_joints;
  std::vector<MeshAsset> meshes;
  std::vector<std::string> body_handlers;
  SourceLocation source;

  const Link& root() const { return links.front(); }
  LinkIndex find_link(std::string_view name) const;
  /// Choreonoid's numJoints: ids 0..max plus every non-fixed link without an id.
  long long num_joints() const;  ///< 2^31 for a joint_id of 2^31 - 1
};

}  // namespace bodyfmt
#pragma GCC visibility pop
