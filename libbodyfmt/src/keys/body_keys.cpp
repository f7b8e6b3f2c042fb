// The key table (body_keys.h). Meanings, units and defaults from body-format-spec §2-§12; the
// order of each node's keys is the order of the loader's did-you-mean candidates.
#include <bodyfmt/body_keys.h>

#include <utility>

namespace bodyfmt {
namespace {

using Keys = std::vector<BodyKey>;
constexpr AngleRule kAngle = AngleRule::kAngle;
constexpr AngleRule kIfRevolute = AngleRule::kAngleIfRevolute;
constexpr AngleRule kAxisAngle = AngleRule::kAxisAngle;

Keys operator+(Keys a, const Keys& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const BodyKey kType{"type", "", "the node's type", "", "", {}, AngleRule::kNone};
const BodyKey kName{"name", "", "the node's name", "", "", {}, AngleRule::kNone};
const BodyKey kTranslation{
    "translation", "", "offset of the node's frame in its parent's frame", "m", "[0, 0, 0]", {}, AngleRule::kNone};
const BodyKey kRotation{"rotation",
                        "",
                        "orientation in the parent's frame: [x, y, z, angle] or a list of them, applied in order",
                        "angle (4th number)",
                        "identity",
                        {},
                        kAxisAngle};
const BodyKey kScale{"scale", "", "scale of the node's frame, per axis", "", "[1, 1, 1]", {}, AngleRule::kNone};
const BodyKey kElements{"elements",      "", "child nodes: shapes, rigid bodies, devices, transforms", "", "", {},
                        AngleRule::kNone};
const BodyKey kCreaseAngle{
    "crease_angle", "creaseAngle", "largest angle between faces that are shaded smooth; normals are generated with it",
    "angle",        "0",           {},
    kAngle};
const BodyKey kDivisionNumber{
    "division_number", "divisionNumber", "tessellation of the primitive (below 4: the default)", "", "20", {},
    AngleRule::kNone};
const BodyKey kUri{"uri",
                   "",
                   "the file, relative to the file that names it (also file://, package://, ${SHARE})",
                   "",
                   "",
                   {},
                   AngleRule::kNone};
const BodyKey kNode{"node",
                    "fragment",
                    "the named part of the file to use (a mesh node, an anchor of a YAML file)",
                    "",
                    "the whole file",
                    {},
                    AngleRule::kNone};
const BodyKey kFragment{"fragment", "node", "the same as node", "", "the whole file", {}, AngleRule::kNone};
const BodyKey kMetadata{"metadata",      "", "how to read the mesh file: length_unit, upper_axis", "", "", {},
                        AngleRule::kNone};
const BodyKey kRemoveRedundant{"remove_redundant_vertices",
                               "removeRedundantVertices",
                               "merge vertices at the same place",
                               "",
                               "false",
                               {},
                               AngleRule::kNone};
const BodyKey kSolid{"solid", "", "VRML's solid flag (one-sided faces); read but unused", "", "", {}, AngleRule::kNone};
const BodyKey kCenterOfMass{"center_of_mass", "centerOfMass", "centre of mass in the frame", "m", "[0, 0, 0]", {},
                            AngleRule::kNone};
const BodyKey kInertia{
    "inertia",       "", "inertia about the centre of mass, frame axes: 9 numbers or 6 (xx xy xz yy yz zz)",
    "kg m^2",        "", {},
    AngleRule::kNone};
const std::vector<std::string_view> kJointTypes = {"fixed", "free", "revolute", "prismatic", "pseudo_continuous_track"};
const BodyKey kJointType{"joint_type", "jointType",     "the joint that connects the link to its parent", "", "fixed",
                         kJointTypes,  AngleRule::kNone};
const BodyKey kJointAxis{
    "joint_axis", "jointAxis",     "the joint's axis in the link frame: [x, y, z], X, Y, Z or -X ...", "", "[0, 0, 1]",
    {},           AngleRule::kNone};
const BodyKey kJointId{"joint_id", "jointId",       "the joint's index in the body's joint vector", "", "-1 (none)",
                       {},         AngleRule::kNone};
const BodyKey kJointRange{"joint_range",
                          "jointRange",
                          "lower and upper joint limit ([lo, hi], or unlimited)",
                          "angle if revolute, else m",
                          "unlimited",
                          {},
                          kIfRevolute};
const BodyKey kMaxJointVelocity{"max_joint_velocity",
                                "maxJointVelocity",
                                "symmetric joint velocity limit",
                                "angle/s if revolute, else m/s",
                                "unlimited",
                                {},
                                kIfRevolute};
const BodyKey kMaterialName{
    "material", "", "contact material name from the simulator's material table", "", "default", {}, AngleRule::kNone};
const BodyKey kParent{"parent",        "", "the parent link's name (every link but the root has one)", "", "", {},
                      AngleRule::kNone};

Keys transform_keys() { return {kType, kName, kTranslation, kRotation, kScale, kElements}; }

Keys scene_header_keys() {
  return {{"format",
           "",
           "the file kind; Choreonoid does not read it",
           "",
           "",
           {"choreonoid_scene", "ChoreonoidScene"},
           AngleRule::kNone},
          {"format_version",
           "formatVersion",
           "the scene format's version: 2.0 reads angles in degrees only",
           "",
           "",
           {"1.0", "2.0"},
           AngleRule::kNone},
          {"angle_unit",
           "angleUnit",
           "the unit of every angle in this scene file, whatever the body file's",
           "",
           "degree",
           {"degree", "radian"},
           AngleRule::kNone},
          {"scene",
           "",
           "the scene's nodes: a list, one node with a type, or a mapping keyed by node type",
           "",
           "",
           {},
           AngleRule::kNone}};
}

Keys header_keys() {
  return {{"format",
           "",
           "the file format; without it the file is a wrapper of another model file",
           "",
           "",
           {"ChoreonoidBody"},
           AngleRule::kNone},
          {"format_version",
           "formatVersion",
           "the format's version: 2.0 reads angles in degrees only",
           "",
           "",
           {"1.0", "2.0"},
           AngleRule::kNone},
          {"angle_unit",
           "angleUnit",
           "the unit of every angle in the file (radian only before format 2.0)",
           "",
           "degree",
           {"degree", "radian"},
           AngleRule::kNone},
          {"name", "", "the model's name", "", "the file name without extension", {}, AngleRule::kNone},
          {"root_link", "rootLink", "the name of the root link", "", "the first link", {}, AngleRule::kNone},
          {"links", "", "the links, in any order: each names its parent", "", "", {}, AngleRule::kNone},
          {"extra_joints", "extraJoints", "joints that close kinematic loops", "", "", {}, AngleRule::kNone},
          {"body_handlers", "", "Choreonoid plugin libraries that handle the body", "", "", {}, AngleRule::kNone},
          {"model_file", "modelFile", "a wrapper's model file (no format key)", "", "", {}, AngleRule::kNone}};
}

Keys link_keys() {
  return {
      {"type",
       "",
       "the node's type: a plain link, or a SubBody or ContinuousTrack node",
       "",
       "Link",
       {"Link", "SubBody", "ContinuousTrack"},
       AngleRule::kNone},
      {"name", "", "the link's name, unique in the body", "", "", {}, AngleRule::kNone},
      kParent,
      {"joint_name", "", "the joint's own name, unique among joint names", "", "the link's name", {}, AngleRule::kNone},
      {"translation",
       "",
       "the link frame (joint position) in the parent link frame; the root's initial position",
       "m",
       "[0, 0, 0]",
       {},
       AngleRule::kNone},
      {"rotation",
       "",
       "the link frame's orientation in the parent link frame: [x, y, z, angle] or a list of them",
       "angle (4th number)",
       "identity",
       {},
       kAxisAngle},
      kJointType,
      kJointAxis,
      kJointId,
      {"actuation_mode",
       "actuationMode",
       "how the joint is driven",
       "",
       "none",
       {"joint_effort", "joint_displacement", "joint_velocity", "link_position"},
       AngleRule::kNone},
      {"joint_angle",
       "jointAngle",
       "initial joint displacement, always converted as an angle",
       "angle",
       "0",
       {},
       kAngle},
      {"joint_displacement",
       "jointDisplacement",
       "initial joint displacement (wins over joint_angle)",
       "angle if revolute, else m",
       "0",
       {},
       kIfRevolute},
      kJointRange,
      kMaxJointVelocity,
      {"joint_velocity_range",
       "jointVelocityRange",
       "joint velocity limits [lo, hi] (unused with max_joint_velocity)",
       "angle/s if revolute, else m/s",
       "unlimited",
       {},
       kIfRevolute},
      {"max_joint_effort",
       "",
       "symmetric joint effort limit",
       "N m if revolute, else N",
       "unlimited",
       {},
       AngleRule::kNone},
      {"joint_axis_inertia",
       "",
       "equivalent rotor inertia (rotor_inertia and gear_ratio are then unused)",
       "kg m^2",
       "0",
       {},
       AngleRule::kNone},
      {"rotor_inertia",
       "rotorInertia",
       "rotor inertia; equivalent = gear_ratio^2 rotor_inertia",
       "kg m^2",
       "0",
       {},
       AngleRule::kNone},
      {"gear_ratio", "gearRatio", "gear ratio of the rotor", "", "1", {}, AngleRule::kNone},
      {"center_of_mass", "centerOfMass", "centre of mass in the link frame", "m", "[0, 0, 0]", {}, AngleRule::kNone},
      {"mass",
       "",
       "the link's mass (with RigidBody elements: added to theirs)",
       "kg",
       "1 without any mass data",
       {},
       AngleRule::kNone},
      {"inertia",
       "",
       "inertia about the centre of mass, link axes: 9 numbers or 6 (xx xy xz yy yz zz)",
       "kg m^2",
       "identity without any mass data",
       {},
       AngleRule::kNone},
      kMaterialName,
      {"elements", "", "the link's shapes, rigid bodies and devices", "", "", {}, AngleRule::kNone},
      {"import",
       "",
       "info keys to add (normally an alias); model keys in it are ignored",
       "",
       "",
       {},
       AngleRule::kNone}};
}

Keys extra_joint_keys() {
  return {{"link1_name", "link1Name", "the first link of the joint", "", "", {}, AngleRule::kNone},
          {"link2_name", "link2Name", "the second link of the joint", "", "", {}, AngleRule::kNone},
          {"joint_type",
           "jointType",
           "the kind of closing joint",
           "",
           "",
           {"fixed", "hinge", "ball", "piston"},
           AngleRule::kNone},
          {"axis",
           "jointAxis",
           "the hinge or piston axis in the joint frame on link1",
           "",
           "[1, 0, 0]",
           {},
           AngleRule::kNone},
          {"translation_in_link1",
           "link1LocalPos",
           "the joint point in link1's frame",
           "m",
           "[0, 0, 0]",
           {},
           AngleRule::kNone},
          {"translation_in_link2",
           "link2LocalPos",
           "the joint point in link2's frame",
           "m",
           "[0, 0, 0]",
           {},
           AngleRule::kNone},
          {"rotation_in_link1",
           "",
           "the joint frame's orientation in link1's frame",
           "angle (4th number)",
           "identity",
           {},
           kAxisAngle},
          {"rotation_in_link2",
           "",
           "the joint frame's orientation in link2's frame",
           "angle (4th number)",
           "identity",
           {},
           kAxisAngle}};
}

Keys subbody_keys() {
  return {{"type", "", "SubBody: include another body file here", "", "", {"SubBody"}, AngleRule::kNone},
          {"uri", "", "the body file to include, relative to this file", "", "", {}, AngleRule::kNone},
          {"prefix", "", "added before every link and joint name of the included body", "", "", {}, AngleRule::kNone},
          {"suffix", "", "added after every link and joint name of the included body", "", "", {}, AngleRule::kNone},
          {"device_prefix", "devicePrefix", "added before every device name", "", "prefix", {}, AngleRule::kNone},
          {"joint_id_offset",
           "jointIdOffset",
           "added to every joint id of the included body",
           "",
           "0",
           {},
           AngleRule::kNone},
          kParent,
          {"name", "", "ignored: the included root link keeps its name", "", "", {}, AngleRule::kNone},
          {"translation", "", "overrides the included root's translation", "m", "", {}, AngleRule::kNone},
          {"rotation", "", "overrides the included root's rotation", "angle (4th number)", "", {}, kAxisAngle},
          kJointType,
          kJointAxis,
          kJointId,
          kJointRange,
          kMaxJointVelocity,
          kMaterialName,
          {"elements", "", "more elements for the included root link", "", "", {}, AngleRule::kNone}};
}

Keys primitive(Keys own) { return own + Keys{kType, kDivisionNumber}; }

Keys mesh_keys() {
  return {{"vertices", "coordinate", "vertex positions, flat x y z", "m", "", {}, AngleRule::kNone},
          {"faces", "coordIndex", "vertex indices of each face", "", "", {}, AngleRule::kNone},
          {"tex_coords", "texCoord", "texture coordinates, flat u v", "", "", {}, AngleRule::kNone},
          {"tex_coord_indices",
           "texCoordIndex",
           "texture coordinate indices per face corner",
           "",
           "",
           {},
           AngleRule::kNone},
          kCreaseAngle,
          {"normals", "", "normal vectors, flat x y z", "", "generated", {}, AngleRule::kNone},
          {"normal_indices", "", "normal indices per face corner", "", "", {}, AngleRule::kNone},
          kSolid,
          kRemoveRedundant,
          kType};
}

const BodyKey kResourceUri{"uri", "", "the mesh or YAML file, relative to this file", "", "", {}, AngleRule::kNone};

Keys device_keys() {
  return {{"type", "", "the device's type", "", "", {}, AngleRule::kNone},
          {"name", "", "the device's name", "", "", {}, AngleRule::kNone},
          {"id", "", "the device's number among devices of its type", "", "-1", {}, AngleRule::kNone},
          {"on", "", "whether the device starts switched on", "", "true", {"true", "false"}, AngleRule::kNone},
          kTranslation,
          kRotation,
          {"elements", "", "shapes attached in the device frame", "", "", {}, AngleRule::kNone}};
}

const BodyKey kOpticalFrame{
    "optical_frame", "", "the sensor frame's convention (gl looks along -Z)", "", "gl", {"gl", "cv", "robotics"},
    AngleRule::kNone};
const BodyKey kOpticalFrameRotation{"optical_frame_rotation",
                                    "",
                                    "rotation applied after the optical frame's",
                                    "angle (4th number)",
                                    "identity",
                                    {},
                                    kAxisAngle};
const BodyKey kMinDistance{"min_distance", "", "nearest distance measured", "m", "0.1", {}, AngleRule::kNone};
const BodyKey kMaxDistance{"max_distance", "", "farthest distance measured", "m", "10", {}, AngleRule::kNone};
const BodyKey kDetectionRate{"detection_rate", "", "share of the points detected", "", "1", {}, AngleRule::kNone};
const BodyKey kErrorDeviation{"error_deviation", "", "standard deviation of the distance error", "m", "0", {},
                              AngleRule::kNone};

Keys camera_keys() {
  return {
      {"format",
       "",
       "what the camera gives: COLOR is a Camera, the others a RangeCamera (required)",
       "",
       "",
       {"COLOR", "DEPTH", "COLOR_DEPTH", "POINT_CLOUD", "COLOR_POINT_CLOUD"},
       AngleRule::kNone},
      {"lens_type", "lensType", "the lens", "", "NORMAL", {"NORMAL", "FISHEYE", "DUAL_FISHEYE"}, AngleRule::kNone},
      {"width", "", "image width", "pixels", "640", {}, AngleRule::kNone},
      {"height", "", "image height", "pixels", "480", {}, AngleRule::kNone},
      {"field_of_view", "fieldOfView", "field of view of the shorter image side", "angle", "45 degrees", {}, kAngle},
      {"near_clip_distance", "nearClipDistance", "nearest distance seen", "m", "0.04", {}, AngleRule::kNone},
      {"far_clip_distance", "farClipDistance", "farthest distance seen", "m", "200", {}, AngleRule::kNone},
      {"frame_rate", "frameRate", "images per second", "Hz", "30", {}, AngleRule::kNone},
      kOpticalFrame,
      kMinDistance,
      kMaxDistance,
      kDetectionRate,
      kErrorDeviation,
      kOpticalFrameRotation};
}

Keys range_sensor_keys() {
  return {{"yaw_range",
           "yawRange,scanAngle",
           "total horizontal scan angle, symmetric about 0",
           "angle",
           "120 degrees",
           {},
           kAngle},
          {"min_yaw_angle", "", "first horizontal angle (with max_yaw_angle)", "angle", "", {}, kAngle},
          {"max_yaw_angle", "", "last horizontal angle (with min_yaw_angle)", "angle", "", {}, kAngle},
          {"yaw_step", "yawStep,scanStep", "horizontal angle between samples", "angle", "1 radian", {}, kAngle},
          {"yaw_samples", "", "number of horizontal samples (instead of yaw_step)", "", "", {}, AngleRule::kNone},
          {"pitch_range", "pitchRange", "total vertical scan angle", "angle", "0", {}, kAngle},
          {"min_pitch_angle", "", "first vertical angle (with max_pitch_angle)", "angle", "", {}, kAngle},
          {"max_pitch_angle", "", "last vertical angle (with min_pitch_angle)", "angle", "", {}, kAngle},
          {"pitch_step", "pitchStep", "vertical angle between samples", "angle", "1 radian", {}, kAngle},
          {"pitch_samples", "", "number of vertical samples (instead of pitch_step)", "", "", {}, AngleRule::kNone},
          {"min_distance", "minDistance", "nearest distance measured", "m", "0.1", {}, AngleRule::kNone},
          {"max_distance", "maxDistance", "farthest distance measured", "m", "10", {}, AngleRule::kNone},
          {"scan_rate", "scanRate", "scans per second", "Hz", "10", {}, AngleRule::kNone},
          {"frame_rate", "", "the same as scan_rate", "Hz", "10", {}, AngleRule::kNone},
          kDetectionRate,
          kErrorDeviation,
          kOpticalFrame,
          kOpticalFrameRotation};
}

Keys light_keys() {
  return {{"color", "", "the light's colour [r, g, b]", "", "[1, 1, 1]", {}, AngleRule::kNone},
          {"intensity", "", "the light's intensity", "", "1", {}, AngleRule::kNone},
          {"attenuation", "", "[constant, linear, quadratic] attenuation", "", "[1, 0, 0]", {}, AngleRule::kNone}};
}

Keys spot_light_keys() {
  return light_keys() +
         Keys{
             {"direction", "", "the direction of the beam in the device frame", "", "[0, 0, -1]", {}, AngleRule::kNone},
             {"beam_width", "beamWidth", "the angle of full intensity", "angle", "90 degrees", {}, kAngle},
             {"cut_off_angle",
              "cutOffAngle",
              "the angle beyond which there is no light",
              "angle",
              "45 degrees",
              {},
              kAngle},
             {"cut_off_exponent", "cutOffExponent", "how fast the light falls off", "", "1", {}, AngleRule::kNone}};
}

const BodyKey kMaxAngularVelocity{"max_angular_velocity",
                                  "maxAngularVelocity",
                                  "largest angular velocity measured, per axis (read raw, not converted)",
                                  "rad/s",
                                  "unlimited",
                                  {},
                                  AngleRule::kNone};
const BodyKey kMaxAcceleration{
    "max_acceleration", "maxAcceleration", "largest acceleration measured, per axis", "m/s^2", "unlimited", {},
    AngleRule::kNone};

Keys continuous_track_keys() {
  return link_keys() +
         Keys{{"numJoints", "", "number of track links (at least 3)", "", "", {}, AngleRule::kNone},
              {"joint_offset", "jointOffset", "offset from one track link to the next", "m", "", {}, AngleRule::kNone},
              {"initialJointAngles",
               "",
               "initial angles of the track joints (numJoints - 1)",
               "angle",
               "0",
               {},
               kAngle}};
}

std::vector<BodyNode> make_nodes() {
  std::vector<BodyNode> nodes = {
      {"body", "Top level", header_keys(), {}},
      {"link", "Link", link_keys(), {}},
      {"link:SubBody", "SubBody node in links", subbody_keys(), {}},
      {"link:ContinuousTrack", "ContinuousTrack node in links", continuous_track_keys(), {}},
      {"extra_joint", "ExtraJoint, an item of extra_joints", extra_joint_keys(), {}},
      {"element:Transform", "Transform, Group and Node elements", transform_keys(), {}},
      {"scene", "Top level of a Choreonoid scene file (.scen) named by a Resource", scene_header_keys(), {}},
      {"scene:Transform",
       "Transform in a scene file: its scale is along the axes of scale_orientation",
       transform_keys() + Keys{{"scale_orientation",
                                "",
                                "orientation of the scale axes (axis-angle, angle in the scene file's unit)",
                                "",
                                "",
                                {},
                                AngleRule::kAxisAngle}},
       {}},
      {"element:Visual",
       "Visual and Collision elements",
       transform_keys() + Keys{{"resource", "", "an inline Resource node", "", "", {}, AngleRule::kNone},
                               {"shape", "", "an inline Shape node", "", "", {}, AngleRule::kNone}},
       {}},
      {"element:RigidBody",
       "RigidBody element",
       transform_keys() +
           Keys{kCenterOfMass, {"mass", "", "the rigid body's mass", "kg", "0", {}, AngleRule::kNone}, kInertia},
       {}},
      {"element:Shape",
       "Shape element",
       transform_keys() +
           Keys{{"geometry", "", "the shape's geometry (a mapping with a type)", "", "", {}, AngleRule::kNone},
                {"appearance", "", "material and texture", "", "", {}, AngleRule::kNone},
                {"is_meta_scene", "", "a scene-only marker", "", "false", {}, AngleRule::kNone}},
       {}},
      {"element:Resource",
       "Resource element",
       {kType, kName, kResourceUri, kNode, kFragment, kMetadata, kTranslation, kRotation, kScale, kCreaseAngle},
       {}},
      {"device", "Device, common keys", device_keys(), {}},
      {"device:Camera",
       "Camera device (also CameraDevice, VisionSensor, RangeCamera)",
       device_keys() + camera_keys(),
       {}},
      {"device:RangeSensor", "RangeSensor device", device_keys() + range_sensor_keys(), {}},
      {"device:PointLight", "PointLight device", device_keys() + light_keys(), {}},
      {"device:SpotLight", "SpotLight device", device_keys() + spot_light_keys(), {}},
      {"device:ForceSensor",
       "ForceSensor device",
       device_keys() +
           Keys{{"max_force", "maxForce", "largest force measured, per axis", "N", "unlimited", {}, AngleRule::kNone},
                {"max_torque",
                 "maxTorque",
                 "largest torque measured, per axis",
                 "N m",
                 "unlimited",
                 {},
                 AngleRule::kNone}},
       {}},
      {"device:RateGyroSensor", "RateGyroSensor device", device_keys() + Keys{kMaxAngularVelocity}, {}},
      {"device:AccelerationSensor", "AccelerationSensor device", device_keys() + Keys{kMaxAcceleration}, {}},
      {"device:IMU",
       "IMU device",
       device_keys() +
           Keys{{"max_angular_velocity", "", kMaxAngularVelocity.meaning, "rad/s", "unlimited", {}, AngleRule::kNone},
                {"max_acceleration", "", kMaxAcceleration.meaning, "m/s^2", "unlimited", {}, AngleRule::kNone}},
       {}},
      {"appearance",
       "appearance of a Shape",
       {{"material", "", "the surface's colours", "", "", {}, AngleRule::kNone},
        {"texture", "", "an image mapped onto the surface", "", "", {}, AngleRule::kNone},
        {"texture_transform",
         "textureTransform",
         "center, scale, translation, rotation of the texture",
         "",
         "",
         {},
         AngleRule::kNone}},
       {}},
      {"material",
       "material of an appearance",
       {{"ambient", "ambientIntensity", "ambient intensity, 0 to 1", "", "1.0", {}, AngleRule::kNone},
        {"diffuse", "diffuseColor", "diffuse colour [r, g, b], 0 to 1", "", "[1, 1, 1]", {}, AngleRule::kNone},
        {"emissive", "emissiveColor", "emitted colour [r, g, b]", "", "[0, 0, 0]", {}, AngleRule::kNone},
        {"specular", "specularColor", "specular colour [r, g, b]", "", "[0, 0, 0]", {}, AngleRule::kNone},
        {"specular_exponent", "", "sharpness of highlights (about 100 looks metallic)", "", "25", {}, AngleRule::kNone},
        {"shininess", "", "deprecated: 0 to 1, used only without specular_exponent", "", "", {}, AngleRule::kNone},
        {"transparency", "", "0 opaque, 1 invisible", "", "0", {}, AngleRule::kNone}},
       {}},
      {"texture",
       "texture of an appearance",
       {{"uri", "url", "the image file, relative to this file", "", "", {}, AngleRule::kNone},
        {"repeat", "", "repeat in s and t: a boolean or [s, t]", "", "true", {}, AngleRule::kNone},
        {"repeat_s", "repeatS", "repeat along s", "", "true", {"true", "false"}, AngleRule::kNone},
        {"repeat_t", "repeatT", "repeat along t", "", "true", {"true", "false"}, AngleRule::kNone}},
       {}},
      {"metadata",
       "metadata of a mesh resource",
       {{"length_unit",
         "",
         "the unit of the mesh file's lengths",
         "",
         "meter",
         {"millimeter", "inch"},
         AngleRule::kNone},
        {"upper_axis", "", "the mesh's up axis (Y: rotated to Z up)", "", "Z", {"Y"}, AngleRule::kNone}},
       {}},
      {"geometry:Box",
       "Box geometry",
       primitive({{"size", "", "full edge lengths along x, y, z", "m", "[1, 1, 1]", {}, AngleRule::kNone}}) +
           Keys{{"extra_division_mode",
                 "",
                 "how extra tessellation is spread",
                 "",
                 "preferred",
                 {"preferred", "x", "y", "z"},
                 AngleRule::kNone}},
       {}},
      {"geometry:Sphere",
       "Sphere geometry",
       primitive({{"radius", "", "the sphere's radius", "m", "1", {}, AngleRule::kNone}}),
       {}},
      {"geometry:Cylinder",
       "Cylinder geometry, along +Y",
       primitive({{"radius", "", "the cylinder's radius", "m", "1", {}, AngleRule::kNone},
                  {"height", "", "the cylinder's length along y", "m", "1", {}, AngleRule::kNone},
                  {"top", "", "with the top cap", "", "true", {"true", "false"}, AngleRule::kNone},
                  {"bottom", "", "with the bottom cap", "", "true", {"true", "false"}, AngleRule::kNone}}),
       {}},
      {"geometry:Cone",
       "Cone geometry, along +Y",
       primitive({{"radius", "", "the base's radius", "m", "1", {}, AngleRule::kNone},
                  {"height", "", "from base (y = -h/2) to apex", "m", "1", {}, AngleRule::kNone},
                  {"bottom", "", "with the base", "", "true", {"true", "false"}, AngleRule::kNone}}),
       {}},
      {"geometry:Capsule",
       "Capsule geometry, along +Y",
       primitive(
           {{"radius", "", "the capsule's radius", "m", "1", {}, AngleRule::kNone},
            {"height", "", "the cylindrical part only (total height + 2 radius)", "m", "1", {}, AngleRule::kNone}}),
       {}},
      {"geometry:Extrusion",
       "Extrusion geometry",
       {{"cross_section",
         "crossSection",
         "the 2-D section in the XZ plane, flat x z pairs",
         "m",
         "",
         {},
         AngleRule::kNone},
        {"spine", "", "the path the section is swept along, flat x y z", "m", "", {}, AngleRule::kNone},
        {"orientation",
         "",
         "the section's rotation at each spine point, flat x y z angle",
         "angle (4th number)",
         "",
         {},
         kAxisAngle},
        {"scale", "", "the section's scale at each spine point, flat sx sz", "", "[1, 1]", {}, AngleRule::kNone},
        kCreaseAngle,
        {"beginCap",
         "",
         "close the start (the snake_case begin_cap is not read by Choreonoid)",
         "",
         "true",
         {"true", "false"},
         AngleRule::kNone},
        {"end_cap", "endCap", "close the end", "", "true", {"true", "false"}, AngleRule::kNone},
        kSolid,
        kType},
       {}},
      {"geometry:ElevationGrid",
       "ElevationGrid geometry",
       {{"x_dimension", "xDimension", "number of grid points along x", "", "0", {}, AngleRule::kNone},
        {"z_dimension", "zDimension", "number of grid points along z", "", "0", {}, AngleRule::kNone},
        {"x_spacing", "xSpacing", "distance between grid points along x", "m", "1", {}, AngleRule::kNone},
        {"z_spacing", "zSpacing", "distance between grid points along z", "m", "1", {}, AngleRule::kNone},
        {"height", "", "x_dimension * z_dimension heights along +Y, x fastest", "m", "", {}, AngleRule::kNone},
        {"ccw", "", "faces are counter-clockwise", "", "true", {"true", "false"}, AngleRule::kNone},
        kCreaseAngle,
        {"tex_coord", "texCoord", "texture coordinates", "", "", {}, AngleRule::kNone},
        kSolid,
        kType},
       {}},
      {"geometry:IndexedFaceSet", "IndexedFaceSet geometry: polygons, each ended by -1", mesh_keys(), {}},
      {"geometry:TriangleMesh", "TriangleMesh geometry: faces are triangles, 3 indices each", mesh_keys(), {}},
      {"geometry:Resource",
       "Resource geometry: one mesh of a file",
       {kResourceUri, kNode, kFragment, kMetadata, kCreaseAngle, kRemoveRedundant, kType},
       {}},
  };
  for (BodyNode& node : nodes)
    for (const BodyKey& key : node.keys) node.names.push_back(key.name);
  return nodes;
}

void append_cell(std::string& out, std::string_view text) {
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
}

}  // namespace

const std::vector<BodyNode>& body_nodes() {
  static const std::vector<BodyNode> nodes = make_nodes();
  return nodes;
}

const BodyNode* find_body_node(std::string_view id) {
  for (const BodyNode& node : body_nodes())
    if (node.id == id) return &node;
  return nullptr;
}

const BodyKey* find_body_key(const BodyNode& node, std::string_view name) {
  for (const BodyKey& key : node.keys)
    if (key.name == name) return &key;
  for (const BodyKey& key : node.keys) {
    std::string_view legacy = key.legacy;
    while (!legacy.empty()) {
      const std::size_t comma = legacy.find(',');
      if (legacy.substr(0, comma) == name) return &key;
      legacy = comma == std::string_view::npos ? std::string_view() : legacy.substr(comma + 1);
    }
  }
  return nullptr;
}

const std::vector<std::string_view>& body_key_names(std::string_view id) {
  static const std::vector<std::string_view> none;
  const BodyNode* node = find_body_node(id);
  return node ? node->names : none;
}

const std::vector<std::string_view>& element_type_names() {
  // The loader's order: its did-you-mean for an unknown type takes the first closest.
  static const std::vector<std::string_view> names = {"Skip",
                                                      "Group",
                                                      "Transform",
                                                      "RigidBody",
                                                      "Visual",
                                                      "Collision",
                                                      "Resource",
                                                      "Shape",
                                                      "LineSet",
                                                      "DirectionalLight",
                                                      "PerspectiveCamera",
                                                      "OrthographicCamera",
                                                      "Fog",
                                                      "Text",
                                                      "Node",
                                                      "ForceSensor",
                                                      "RateGyroSensor",
                                                      "AccelerationSensor",
                                                      "IMU",
                                                      "Camera",
                                                      "CameraDevice",
                                                      "RangeSensor",
                                                      "PointLight",
                                                      "SpotLight",
                                                      "DigitalIO",
                                                      "Holder",
                                                      "Attachment",
                                                      "Conveyor",
                                                      "ZmpDevice",
                                                      "MarkerDevice"};
  return names;
}

const std::vector<std::string_view>& geometry_type_names() {
  static const std::vector<std::string_view> names = {"Box",          "Sphere",    "Cylinder",      "Cone",
                                                      "Capsule",      "Extrusion", "ElevationGrid", "IndexedFaceSet",
                                                      "TriangleMesh", "Resource"};
  return names;
}

const std::vector<std::string_view>& device_type_names() {
  static const std::vector<std::string_view> names = {
      "ForceSensor",  "RateGyroSensor", "AccelerationSensor", "IMU",       "Camera",
      "CameraDevice", "RangeSensor",    "PointLight",         "SpotLight", "DigitalIO",
      "Holder",       "Attachment",     "Conveyor",           "ZmpDevice", "MarkerDevice"};
  // Not VisionSensor or RangeCamera: those are device classes that Choreonoid registers no
  // reader for (RangeCamera only writes itself as a Camera), so a node of either type is an
  // unknown node type there, and refuses the file unless it is optional.
  return names;
}

std::string describe_body_key(const BodyKey& key, std::string_view angle_unit) {
  std::string out = std::string(key.meaning);
  if (!key.unit.empty()) {
    // "angle", "angle/s if revolute, else m/s", "angle (4th number)": the word is the unit.
    std::string unit(key.unit);
    if (key.angle != AngleRule::kNone)
      for (std::size_t at = unit.find("angle"); at != std::string::npos;
           at = unit.find("angle", at + angle_unit.size()))
        unit.replace(at, 5, angle_unit);
    out += "; unit: " + unit;
  }
  if (!key.default_value.empty()) out += "; default: " + std::string(key.default_value);
  if (!key.values.empty()) {
    out += "; values:";
    for (std::string_view v : key.values) out += " " + std::string(v);
  }
  return out;
}

std::string body_keys_markdown() {
  std::string out =
      "# Body-format keys\n\n"
      "Every key bodyfmt reads, per kind of node: what it means, its unit and its default (from\n"
      "body-format-spec.md). Generated from libbodyfmt's key table (libbodyfmt/src/keys/body_keys.cpp),\n"
      "which is also the loader's list of known keys and what `bodyls` shows on hover: run\n"
      "`./build/keys_doc > docs/keys.md` after changing it. \"angle\" is in the file's angle unit\n"
      "(degrees unless `angle_unit: radian` in a format 1.0 file).\n";
  for (const BodyNode& node : body_nodes()) {
    out += "\n## " + std::string(node.title) + "\n\n| key | also | meaning | unit | default | values |\n";
    out += "|---|---|---|---|---|---|\n";
    for (const BodyKey& key : node.keys) {
      out += "| `" + std::string(key.name) + "` | ";
      append_cell(out, key.legacy);
      out += " | ";
      append_cell(out, key.meaning);
      out += " | ";
      append_cell(out, key.unit);
      out += " | ";
      append_cell(out, key.default_value);
      out += " | ";
      for (std::size_t i = 0; i < key.values.size(); ++i) out += (i ? ", `" : "`") + std::string(key.values[i]) + "`";
      out += " |\n";
    }
  }
  return out;
}

}  // namespace bodyfmt
