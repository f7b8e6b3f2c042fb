// choreonoid_dump: loads one .body file (or .urdf, or a wrapper around one, when Choreonoid's
// URDF loader is linked in: CMakeLists.txt) with Choreonoid's own BodyLoader and prints what that
// loader computed, in the reference schema of shared/corpus/README.md. It is the independent
// side of the conformance check: every value here comes from Choreonoid, none from bodyfmt.
// Built against a Choreonoid build by hand (README.md), never by the project or its CI.
//
// usage: choreonoid_dump FILE.body   (exit 0 when Choreonoid loads it, 1 when it refuses it,
//                                     2 on a usage error; the YAML goes to stdout either way)
#include <cnoid/Body>
#include <cnoid/BodyLoader>
#include <cnoid/BoundingBox>
#include <cnoid/Camera>
#include <cnoid/Device>
#include <cnoid/Link>
#include <cnoid/SceneGraph>
#include <cnoid/SpotLight>
#ifdef CHOREONOID_DUMP_WITH_ASSIMP
#include <cnoid/AssimpSceneLoader>
#endif

#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>

namespace {

// Twelve significant digits: enough for the 1e-9 relative tolerance of the references, and
// short enough to read. Infinite values are YAML's .inf, as the references write them.
std::string number(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char text[64];
  std::snprintf(text, sizeof text, "%.12g", v);
  return text;
}

// Choreonoid marks an unlimited range with +-DBL_MAX (Link::isUnlimitedRangeValue); the
// schema writes it as an infinity.
std::string rangeValue(double v) {
  if (cnoid::Link::isUnlimitedRangeValue(v)) return v > 0 ? ".inf" : "-.inf";
  return number(v);
}

// A YAML double-quoted scalar: names and loader messages may hold quotes or line breaks.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          char esc[8];
          std::snprintf(esc, sizeof esc, "\\x%02x", c);
          out += esc;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

template <class Vector>
std::string vector3(const Vector& v) {
  return "[" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + "]";
}

template <class Matrix>
std::string matrix3(const Matrix& m) {  // row-major, as the schema says
  std::string out = "[";
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out += (row || col ? ", " : "") + number(m(row, col));
  }
  return out + "]";
}

const char* jointTypeName(const cnoid::Link* link) {
  switch (link->jointType()) {
    case cnoid::Link::RevoluteJoint: return "revolute";
    case cnoid::Link::PrismaticJoint: return "prismatic";
    case cnoid::Link::FreeJoint: return "free";
    case cnoid::Link::FixedJoint: return "fixed";
    case cnoid::Link::PseudoContinuousTrackJoint: return "pseudo_continuous_track";
  }
  return "unknown";
}

// The box Choreonoid's scene graph gives for a link's shape group, in the link frame; an empty
// group (a link without that kind of shape) prints nothing, as in the references.
void printBox(std::ostream& out, const char* key, cnoid::SgNode* shape) {
  if (!shape) return;
  const cnoid::BoundingBox& box = shape->boundingBox();
  if (box.empty()) return;
  const cnoid::Vector3& lo = box.min();
  const cnoid::Vector3& hi = box.max();
  out << "  " << key << ": [" << number(lo.x()) << ", " << number(lo.y()) << ", " << number(lo.z()) << ", "
      << number(hi.x()) << ", " << number(hi.y()) << ", " << number(hi.z()) << "]\n";
}

void printLink(std::ostream& out, cnoid::Link* link) {
  out << "- name: " << quoted(link->name()) << "\n";
  out << "  parent: " << (link->parent() ? quoted(link->parent()->name()) : std::string("null")) << "\n";
  out << "  joint_type: " << jointTypeName(link) << "\n";
  out << "  joint_id: " << link->jointId() << "\n";
  out << "  joint_axis: " << vector3(link->jointAxis()) << "\n";
  out << "  joint_range: [" << rangeValue(link->q_lower()) << ", " << rangeValue(link->q_upper()) << "]\n";
  out << "  joint_velocity_range: [" << rangeValue(link->dq_lower()) << ", " << rangeValue(link->dq_upper()) << "]\n";
  out << "  mass: " << number(link->mass()) << "\n";
  out << "  center_of_mass: " << vector3(link->centerOfMass()) << "\n";
  out << "  inertia: " << matrix3(link->I()) << "\n";
  if (link->parent()) {
    out << "  translation: " << vector3(link->offsetTranslation()) << "\n";
    out << "  rotation: " << matrix3(link->offsetRotation()) << "\n";
  }
  out << "  world_translation_at_zero: " << vector3(link->translation()) << "\n";
  printBox(out, "visual_bbox", link->visualShape());
  printBox(out, "collision_bbox", link->collisionShape());
}

void printDevice(std::ostream& out, cnoid::Device* device) {
  out << "- name: " << quoted(device->name()) << "\n";
  out << "  type: " << device->typeName() << "\n";
  out << "  link: " << (device->link() ? quoted(device->link()->name()) : std::string("null")) << "\n";
  out << "  translation: " << vector3(device->localTranslation()) << "\n";
  out << "  rotation: " << matrix3(device->localRotation()) << "\n";
  if (auto camera = dynamic_cast<cnoid::Camera*>(device)) {  // RangeCamera is a Camera too
    out << "  field_of_view: " << number(camera->fieldOfView()) << "\n";
    out << "  resolution: [" << camera->resolutionX() << ", " << camera->resolutionY() << "]\n";
    out << "  near_clip_distance: " << number(camera->nearClipDistance()) << "\n";
    out << "  far_clip_distance: " << number(camera->farClipDistance()) << "\n";
  }
  if (auto light = dynamic_cast<cnoid::SpotLight*>(device)) {
    out << "  direction: " << vector3(light->direction()) << "\n";
    out << "  beam_width: " << number(light->beamWidth()) << "\n";
    out << "  cut_off_angle: " << number(light->cutOffAngle()) << "\n";
    out << "  cut_off_exponent: " << number(light->cutOffExponent()) << "\n";
  }
}

void printBody(std::ostream& out, cnoid::Body* body, const std::string& messages) {
  // Link origins relative to the root with every joint at zero: Choreonoid's own forward
  // kinematics from an identity root, not the root pose or initial angles of the file.
  cnoid::Link* root = body->rootLink();
  const cnoid::Isometry3 rootOffset = root->Tb();
  for (int i = 0; i < body->numLinks(); ++i) body->link(i)->q() = 0.0;
  root->T().setIdentity();
  body->calcForwardKinematics();
  body->calcCenterOfMass();  // also sums the link masses into Body::mass()

  out << "loaded: true\n";
  out << "model_name: " << quoted(body->modelName()) << "\n";
  out << "total_mass: " << number(body->mass()) << "\n";
  out << "num_links: " << body->numLinks() << "\n";
  out << "num_joints: " << body->numJoints() << "\n";
  out << "root_translation: " << vector3(rootOffset.translation()) << "\n";
  out << "root_rotation: " << matrix3(rootOffset.linear()) << "\n";
  out << "links:\n";
  for (int i = 0; i < body->numLinks(); ++i) printLink(out, body->link(i));
  out << "devices:\n";
  for (int i = 0; i < body->numDevices(); ++i) printDevice(out, body->device(i));
  out << "extra_joints: " << body->numExtraJoints() << "\n";
  out << "messages: " << quoted(messages) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: choreonoid_dump FILE.body\n";
    return 2;
  }
#ifdef CHOREONOID_DUMP_WITH_ASSIMP
  // Collada and the other Assimp formats, as in a Choreonoid built with Assimp.
  cnoid::AssimpSceneLoader::initializeClass();
#endif
  std::ostringstream messages;
  cnoid::BodyLoader loader;
  loader.setMessageSink(messages);
  cnoid::BodyPtr body = new cnoid::Body;
  bool loaded = false;
  try {
    loaded = loader.load(body, argv[1]);
  } catch (const std::exception& e) {  // Choreonoid reports most failures itself; keep any other
    messages << e.what();
  }
  std::cout << "# Choreonoid's own BodyLoader values (tests/corpus/choreonoid_dump).\n";
  if (!loaded || !body->rootLink()) {
    std::cout << "loaded: false\nmessages: " << quoted(messages.str()) << "\n";
    return 1;
  }
  printBody(std::cout, body, messages.str());
  return 0;
}
