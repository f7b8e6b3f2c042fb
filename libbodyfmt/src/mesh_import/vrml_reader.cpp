#include "mesh_import/vrml_reader.h"

#include "mesh_import/primitives.h"
#include "mesh_import/vrml_lexer.h"

#include <bodyfmt/rules.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>

namespace bodyfmt::mesh {

namespace {

constexpr int kMaxDepth = 200;  // nesting guard: malformed input must not overflow the stack

enum class NodeKind { kNone, kScene, kAppearance, kMaterial, kTexture, kGeometry, kCoordinate, kTextureCoordinate };

/// One parsed VRML node, reduced to what the geometry needs.
struct VrmlNode {
  NodeKind kind = NodeKind::kNone;
  std::shared_ptr<const SceneNode> scene;                       // Transform, Group, Shape, Inline
  std::optional<Material> material;                             // Material, Appearance
  std::optional<Texture> texture;                               // ImageTexture, Appearance
  std::shared_ptr<const TriangleMesh> geometry;                 // geometry nodes
  std::shared_ptr<const std::vector<Eigen::Vector3d>> points;   // Coordinate
  std::shared_ptr<const std::vector<Eigen::Vector2d>> points2;  // TextureCoordinate
};

using NodePtr = std::shared_ptr<const VrmlNode>;

class Parser {
 public:
  Parser(std::string_view text, const std::string& path, DiagnosticSink& sink, const InlineLoader& load_inline)
      : lexer_(text), path_(path), sink_(sink), load_inline_(load_inline) {}

  SceneTree parse_file() {
    auto root = std::make_shared<SceneNode>();
    while (!failed_ && lexer_.peek().kind != TokenKind::kEnd) {
      if (skip_statement()) continue;
      NodePtr node = parse_node();
      if (node && node->scene) root->children.push_back(node->scene);
    }
    if (failed_) return nullptr;
    return root;
  }

 private:
  // -- diagnostics -------------------------------------------------------------------------
  void fail(const Token& at, const std::string& message) {
    if (failed_) return;
    failed_ = true;
    report("mesh-parse", at, "VRML: " + message);
  }
  void report(std::string_view rule, const Token& at, std::string message) {
    report_rule(sink_, rule, {path_, at.line, at.column}, std::move(message));
  }
  static std::string describe(const Token& t) {
    switch (t.kind) {
      case TokenKind::kEnd: return "end of file";
      case TokenKind::kString: return "string \"" + std::string(t.text) + "\"";
      case TokenKind::kError: return std::string(t.text);
      default: return "\"" + std::string(t.text) + "\"";
    }
  }
  bool expect(TokenKind kind, const char* what) {
    Token t = lexer_.next();
    if (t.kind == kind) return true;
    fail(t, std::string("expected ") + what + ", found " + describe(t));
    return false;
  }

  // -- generic skipping -----------------------------------------------------------------
  /// Top-level statements that are not nodes: PROTO, EXTERNPROTO, ROUTE. Returns true when one
  /// was skipped.
  bool skip_statement() {
    const Token& t = lexer_.peek();
    if (t.kind != TokenKind::kIdentifier) return false;
    if (t.text == "PROTO") {
      lexer_.next();
      lexer_.next();  // name
      skip_group(TokenKind::kOpenBracket, TokenKind::kCloseBracket, "\"[\" of the PROTO interface");
      skip_group(TokenKind::kOpenBrace, TokenKind::kCloseBrace, "\"{\" of the PROTO body");
      return true;
    }
    if (t.text == "EXTERNPROTO") {
      lexer_.next();
      lexer_.next();  // name
      skip_group(TokenKind::kOpenBracket, TokenKind::kCloseBracket, "\"[\" of the EXTERNPROTO interface");
      skip_value();  // url(s)
      return true;
    }
    if (t.text == "ROUTE") {  // ROUTE a.b TO c.d
      for (int i = 0; i < 4 && !failed_; ++i) {
        Token r = lexer_.next();
        if (r.kind != TokenKind::kIdentifier) fail(r, "malformed ROUTE statement");
      }
      return true;
    }
    return false;
  }

  /// Skips a bracketed or braced group, matching nested brackets and braces.
  void skip_group(TokenKind open, TokenKind close, const char* what) {
    if (!expect(open, what)) return;
    std::vector<TokenKind> stack{close};
    while (!stack.empty()) {
      Token t = lexer_.next();
      switch (t.kind) {
        case TokenKind::kOpenBrace: stack.push_back(TokenKind::kCloseBrace); break;
        case TokenKind::kOpenBracket: stack.push_back(TokenKind::kCloseBracket); break;
        case TokenKind::kCloseBrace:
        case TokenKind::kCloseBracket:
          if (t.kind != stack.back()) return fail(t, "unbalanced " + describe(t));
          stack.pop_back();
          break;
        case TokenKind::kEnd: return fail(t, "unexpected end of file inside a skipped node");
        case TokenKind::kError: return fail(t, std::string(t.text));
        default: break;
      }
    }
  }

  /// Skips the value of a field we do not read: a list, a node, or a run of scalars.
  void skip_value() {
    const Token& t = lexer_.peek();
    switch (t.kind) {
      case TokenKind::kOpenBracket: skip_group(TokenKind::kOpenBracket, TokenKind::kCloseBracket, "\"[\""); return;
      case TokenKind::kNumber:
      case TokenKind::kString:
        while (lexer_.peek().kind == TokenKind::kNumber || lexer_.peek().kind == TokenKind::kString) {
          lexer_.next();
        }
        return;
      case TokenKind::kIdentifier:
        if (t.text == "TRUE" || t.text == "FALSE") {
          lexer_.next();
          return;
        }
        parse_node();  // a node value (also DEF/USE/NULL); unknown types are brace-skipped
        return;
      default: {
        Token bad = lexer_.next();
        fail(bad, "expected a field value, found " + describe(bad));
      }
    }
  }

  // -- scalar values ----------------------------------------------------------------------
  double read_number() {
    Token t = lexer_.next();
    if (t.kind != TokenKind::kNumber) {
      fail(t, "expected a number, found " + describe(t));
      return 0;
    }
    return to_double(t);
  }
  double to_double(const Token& t) {
    std::string_view s = t.text;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    if (s.size() > 2 && (s.substr(0, 2) == "0x" || s.substr(0, 2) == "0X")) {
      return static_cast<double>(std::strtoll(std::string(s).c_str(), nullptr, 16));
    }
    double value = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || end != s.data() + s.size()) {
      fail(t, "malformed number \"" + std::string(t.text) + "\"");
      return 0;
    }
    return value;
  }
  bool read_bool() {
    Token t = lexer_.next();
    if (t.kind == TokenKind::kIdentifier && (t.text == "TRUE" || t.text == "FALSE")) {
      return t.text == "TRUE";
    }
    fail(t, "expected TRUE or FALSE, found " + describe(t));
    return false;
  }
  Eigen::Vector3d read_vec3() {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = read_number();
    return v;
  }
  Eigen::AngleAxisd read_rotation() {
    const Eigen::Vector3d axis = read_vec3();
    const double angle = read_number();
    if (axis.norm() < 1e-12) return Eigen::AngleAxisd(0, Eigen::Vector3d::UnitZ());
    return Eigen::AngleAxisd(angle, axis.normalized());
  }
  /// MF numeric field: `[ n n ... ]` or a bare run of numbers, each read by `read_one`.
  template <typename T, typename ReadOne>
  std::vector<T> read_list(ReadOne read_one) {
    std::vector<T> values;
    if (lexer_.peek().kind == TokenKind::kOpenBracket) {
      lexer_.next();
      while (!failed_ && lexer_.peek().kind != TokenKind::kCloseBracket) values.push_back(read_one());
      if (!failed_) lexer_.next();
    } else {
      values.push_back(read_one());
      while (!failed_ && lexer_.peek().kind == TokenKind::kNumber) values.push_back(read_one());
    }
    return values;
  }
  std::vector<double> read_numbers() {
    return read_list<double>([this] { return read_number(); });
  }
  /// MFInt32 (indices): a number that is not an integer within int range is an error at it,
  /// not a wrapped or undefined conversion.
  std::vector<int> read_ints() {
    return read_list<int>([this] {
      const Token t = lexer_.peek();
      const double v = read_number();
      if (failed_) return 0;
      if (!(v == std::floor(v) && std::abs(v) <= std::numeric_limits<int>::max())) {
        fail(t, "expected a 32-bit integer, found " + describe(t));
        return 0;
      }
      return static_cast<int>(v);
    });
  }
  std::vector<std::string> read_strings() {
    std::vector<std::string> values;
    const bool list = lexer_.peek().kind == TokenKind::kOpenBracket;
    if (list) lexer_.next();
    do {
      if (list && lexer_.peek().kind == TokenKind::kCloseBracket) break;
      Token t = lexer_.next();
      if (t.kind != TokenKind::kString) {
        fail(t, "expected a string, found " + describe(t));
        break;
      }
      values.push_back(unescape_string(t.text));
    } while (list && !failed_);
    if (list && !failed_) expect(TokenKind::kCloseBracket, "\"]\"");
    return values;
  }
  /// MFNode field: `[ node ... ]` or a single node.
  std::vector<NodePtr> read_nodes() {
    std::vector<NodePtr> nodes;
    if (lexer_.peek().kind == TokenKind::kOpenBracket) {
      lexer_.next();
      while (!failed_ && lexer_.peek().kind != TokenKind::kCloseBracket) {
        if (skip_statement()) continue;  // PROTO/ROUTE may appear among children
        nodes.push_back(parse_node());
      }
      if (!failed_) lexer_.next();
    } else {
      nodes.push_back(parse_node());
    }
    return nodes;
  }

  // -- nodes --------------------------------------------------------------------------------
  NodePtr parse_node() {
    if (failed_) return nullptr;
    Token first = lexer_.next();
    if (first.kind != TokenKind::kIdentifier) {
      fail(first, "expected a node, found " + describe(first));
      return nullptr;
    }
    if (first.text == "NULL") return nullptr;
    if (first.text == "USE") {
      Token name = lexer_.next();
      auto it = defs_.find(std::string(name.text));
      if (name.kind != TokenKind::kIdentifier || it == defs_.end()) {
        fail(name, "USE of an undefined name " + describe(name));
        return nullptr;
      }
      return it->second;
    }
    std::string def_name;
    Token type = first;
    if (first.text == "DEF") {
      Token name = lexer_.next();
      if (name.kind != TokenKind::kIdentifier) {
        fail(name, "expected a name after DEF, found " + describe(name));
        return nullptr;
      }
      if (lexer_.peek().kind == TokenKind::kOpenBrace) {
        // `DEF Transform {` (Tank/resource/tank.wrl): Choreonoid reads an unnamed Transform.
        type = name;
      } else {
        def_name = std::string(name.text);
        type = lexer_.next();
        if (type.kind != TokenKind::kIdentifier) {
          fail(type, "expected a node type after DEF " + def_name + ", found " + describe(type));
          return nullptr;
        }
      }
    }
    if (lexer_.peek().kind != TokenKind::kOpenBrace) {
      Token t = lexer_.next();
      fail(t, "expected \"{\" after node type \"" + std::string(type.text) + "\", found " + describe(t));
      return nullptr;
    }
    if (++depth_ > kMaxDepth) {
      fail(type, "nodes nested deeper than " + std::to_string(kMaxDepth) + " levels");
      return nullptr;
    }
    NodePtr node = parse_body(type, def_name);
    --depth_;
    if (failed_) return nullptr;
    // DEF binds the name from here on (VRML97 §4.6.2); a later DEF of the same name rebinds.
    if (!def_name.empty()) defs_[def_name] = node;
    return node;
  }

  /// Reads `{ fields }`, calling `field(name_token)` for each field name; the callback reads
  /// the value and returns false for fields it does not know (then skipped).
  template <typename F>
  void read_fields(F&& field) {
    lexer_.next();  // '{'
    while (!failed_) {
      const Token& t = lexer_.peek();
      if (t.kind == TokenKind::kCloseBrace) {
        lexer_.next();
        return;
      }
      Token name = lexer_.next();
      if (name.kind != TokenKind::kIdentifier) {
        fail(name, "expected a field name or \"}\", found " + describe(name));
        return;
      }
      // Inside PROTO bodies / scripts only; harmless to skip.
      if (name.text == "ROUTE") {
        for (int i = 0; i < 3; ++i) lexer_.next();
        continue;
      }
      if (!field(name)) skip_value();
    }
  }

  NodePtr parse_body(const Token& type, const std::string& def_name) {
    const std::string_view t = type.text;
    if (t == "Transform") return parse_grouping(type, def_name, true);
    if (t == "Group" || t == "Anchor" || t == "Billboard" || t == "Collision" || t == "Switch" || t == "LOD") {
      return parse_grouping(type, def_name, false);
    }
    if (t == "Shape") return parse_shape(def_name);
    if (t == "Appearance") return parse_appearance();
    if (t == "Material") return parse_material();
    if (t == "ImageTexture") return parse_image_texture();
    if (t == "IndexedFaceSet") return parse_indexed_face_set(type);
    if (t == "Coordinate" || t == "TextureCoordinate") return parse_coordinate(t == "Coordinate");
    if (t == "Box" || t == "Sphere" || t == "Cylinder" || t == "Cone") return parse_primitive(type);
    if (t == "Inline") return parse_inline(type, def_name);
    // Everything else (Viewpoint, NavigationInfo, lights, PROTO instances, IndexedLineSet...)
    // carries no surface Choreonoid turns into a body mesh: skip it by brace matching.
    skip_group(TokenKind::kOpenBrace, TokenKind::kCloseBrace, "\"{\"");
    return std::make_shared<VrmlNode>();
  }

  NodePtr parse_grouping(const Token& type, const std::string& def_name, bool is_transform) {
    auto scene = std::make_shared<SceneNode>();
    scene->name = def_name;
    Eigen::Vector3d translation = Eigen::Vector3d::Zero(), center = Eigen::Vector3d::Zero(),
                    scale = Eigen::Vector3d::Ones();
    Eigen::AngleAxisd rotation(0, Eigen::Vector3d::UnitZ()), scale_orientation(0, Eigen::Vector3d::UnitZ());
    int which_choice = -1;
    std::vector<NodePtr> children;
    const bool is_switch = type.text == "Switch";
    const bool is_lod = type.text == "LOD";
    read_fields([&](const Token& f) {
      const std::string_view n = f.text;
      if (n == "children" || (is_switch && n == "choice") || (is_lod && n == "level")) {
        children = read_nodes();
      } else if (n == "proxy") {
        skip_value();  // Collision proxy: never rendered
      } else if (is_switch && n == "whichChoice") {
        which_choice = static_cast<int>(read_number());
      } else if (!is_transform) {
        return false;
      } else if (n == "translation") {
        translation = read_vec3();
      } else if (n == "rotation") {
        rotation = read_rotation();
      } else if (n == "scale") {
        scale = read_vec3();
      } else if (n == "scaleOrientation") {
        scale_orientation = read_rotation();
      } else if (n == "center") {
        center = read_vec3();
      } else {
        return false;
      }
      return true;
    });
    if (failed_) return nullptr;
    if (is_switch) {  // only the chosen child is part of the scene
      std::vector<NodePtr> chosen;
      if (which_choice >= 0 && which_choice < static_cast<int>(children.size())) {
        chosen.push_back(children[static_cast<std::size_t>(which_choice)]);
      }
      children.swap(chosen);
    } else if (is_lod && children.size() > 1) {
      children.resize(1);  // the most detailed level
    }
    if (is_transform) {
      // VRML97 §6.52: P' = T C R SR S -SR -C P.
      Eigen::Affine3d m = Eigen::Affine3d::Identity();
      m.translate(translation)
          .translate(center)
          .rotate(rotation)
          .rotate(scale_orientation)
          .scale(scale)
          .rotate(scale_orientation.inverse())
          .translate(-center);
      scene->transform = m;
    }
    for (const NodePtr& child : children) {
      if (child && child->scene) scene->children.push_back(child->scene);
    }
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kScene;
    node->scene = scene;
    return node;
  }

  NodePtr parse_shape(const std::string& def_name) {
    NodePtr appearance, geometry;
    read_fields([&](const Token& f) {
      if (f.text == "appearance")
        appearance = parse_node();
      else if (f.text == "geometry")
        geometry = parse_node();
      else
        return false;
      return true;
    });
    if (failed_) return nullptr;
    auto scene = std::make_shared<SceneNode>();
    scene->name = def_name;
    if (geometry && geometry->geometry) {
      MeshPart part;
      part.mesh = *geometry->geometry;
      if (appearance) {
        part.material = appearance->material;
        part.texture = appearance->texture;
      }
      scene->parts.push_back(std::move(part));
    }
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kScene;
    node->scene = scene;
    return node;
  }

  NodePtr parse_appearance() {
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kAppearance;
    read_fields([&](const Token& f) {
      if (f.text == "material") {
        if (NodePtr m = parse_node()) node->material = m->material;
      } else if (f.text == "texture") {
        if (NodePtr t = parse_node()) node->texture = t->texture;
      } else {
        return false;  // textureTransform
      }
      return true;
    });
    return node;
  }

  NodePtr parse_material() {
    // VRML97 §6.27 defaults; Choreonoid maps shininess to 127 * shininess + 1 (spec §8.7).
    Material m;
    m.diffuse_color = Eigen::Vector3d::Constant(0.8);
    m.ambient_intensity = 0.2;
    double shininess = 0.2;
    read_fields([&](const Token& f) {
      const std::string_view n = f.text;
      if (n == "diffuseColor")
        m.diffuse_color = read_vec3();
      else if (n == "ambientIntensity")
        m.ambient_intensity = read_number();
      else if (n == "emissiveColor")
        m.emissive_color = read_vec3();
      else if (n == "specularColor")
        m.specular_color = read_vec3();
      else if (n == "shininess")
        shininess = read_number();
      else if (n == "transparency")
        m.transparency = read_number();
      else
        return false;
      return true;
    });
    m.specular_exponent = 127.0 * std::clamp(shininess, 0.0, 1.0) + 1.0;
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kMaterial;
    node->material = m;
    return node;
  }

  NodePtr parse_image_texture() {
    Texture texture;
    read_fields([&](const Token& f) {
      if (f.text == "url") {
        const auto urls = read_strings();
        if (!urls.empty()) {
          texture.uri = urls.front();
          texture.resolved_path = resolve_relative(path_, texture.uri);
        }
      } else if (f.text == "repeatS") {
        texture.repeat_s = read_bool();
      } else if (f.text == "repeatT") {
        texture.repeat_t = read_bool();
      } else {
        return false;
      }
      return true;
    });
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kTexture;
    if (!texture.uri.empty()) node->texture = texture;
    return node;
  }

  NodePtr parse_coordinate(bool three_d) {
    std::vector<double> values;
    read_fields([&](const Token& f) {
      if (f.text != "point") return false;
      values = read_numbers();
      return true;
    });
    auto node = std::make_shared<VrmlNode>();
    if (three_d) {
      auto points = std::make_shared<std::vector<Eigen::Vector3d>>();
      points->reserve(values.size() / 3);
      for (std::size_t i = 0; i + 2 < values.size(); i += 3)
        points->emplace_back(values[i], values[i + 1], values[i + 2]);
      node->kind = NodeKind::kCoordinate;
      node->points = points;
    } else {
      auto points = std::make_shared<std::vector<Eigen::Vector2d>>();
      for (std::size_t i = 0; i + 1 < values.size(); i += 2) points->emplace_back(values[i], values[i + 1]);
      node->kind = NodeKind::kTextureCoordinate;
      node->points2 = points;
    }
    return node;
  }

  NodePtr parse_indexed_face_set(const Token& type) {
    NodePtr coord, tex_coord;
    std::vector<int> coord_index, tex_coord_index;
    bool ccw = true;
    read_fields([&](const Token& f) {
      const std::string_view n = f.text;
      if (n == "coord")
        coord = parse_node();
      else if (n == "coordIndex")
        coord_index = read_ints();
      else if (n == "texCoord")
        tex_coord = parse_node();
      else if (n == "texCoordIndex")
        tex_coord_index = read_ints();
      else if (n == "ccw")
        ccw = read_bool();
      else
        return false;  // solid, creaseAngle, normal, color...: not needed for the surface
      return true;
    });
    if (failed_) return nullptr;
    auto mesh = std::make_shared<TriangleMesh>();
    const std::vector<Eigen::Vector3d> no_points;
    const auto& points = (coord && coord->points) ? *coord->points : no_points;
    const bool textured = tex_coord && tex_coord->points2 && !tex_coord->points2->empty();
    const std::vector<int>& tc_index = tex_coord_index.empty() ? coord_index : tex_coord_index;
    const int n_points = static_cast<int>(points.size());
    const int n_tex = textured ? static_cast<int>(tex_coord->points2->size()) : 0;

    // Without texture coordinates the Coordinate points are the vertices as they are (as in
    // Choreonoid, so unused points still count in the bounding box); with them, each distinct
    // (point, texture point) pair becomes a vertex.
    std::map<std::pair<int, int>, int> corner_vertex;
    if (!textured) mesh->vertices = points;
    const auto vertex_of = [&](std::size_t corner) -> int {
      const int p = coord_index[corner];
      if (!textured) return p;
      int t = corner < tc_index.size() ? tc_index[corner] : -1;
      if (t < 0 || t >= n_tex) t = -1;
      auto [it, inserted] = corner_vertex.emplace(std::make_pair(p, t), static_cast<int>(mesh->vertices.size()));
      if (inserted) {
        mesh->vertices.push_back(points[static_cast<std::size_t>(p)]);
        mesh->tex_coords.push_back(t >= 0 ? (*tex_coord->points2)[static_cast<std::size_t>(t)]
                                          : Eigen::Vector2d::Zero());
      }
      return it->second;
    };

    int bad_index = -1;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= coord_index.size(); ++i) {
      // VRML97 lets the last polygon go without its -1 terminator.
      if (i < coord_index.size() && coord_index[i] >= 0) continue;
      const std::size_t count = i - start;
      bool valid = count >= 3;
      for (std::size_t k = start; k < i && valid; ++k) {
        if (coord_index[k] >= n_points) {
          bad_index = coord_index[k];
          valid = false;
        }
      }
      if (valid) {
        // Fan triangulation: the corpus polygons are triangles, quads and convex fans.
        const int a = vertex_of(start);
        for (std::size_t k = start + 1; k + 1 < i; ++k) {
          int b = vertex_of(k), c = vertex_of(k + 1);
          if (!ccw) std::swap(b, c);
          mesh->triangles.push_back({a, b, c});
        }
      }
      start = i + 1;
    }
    if (bad_index >= 0) {
      report("mesh-invalid-geometry", type,
             "IndexedFaceSet: vertex index " + std::to_string(bad_index) + " is over the number of vertices (" +
                 std::to_string(n_points) + "); polygons using it were dropped");
    }
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kGeometry;
    node->geometry = mesh;
    return node;
  }

  NodePtr parse_primitive(const Token& type) {
    const std::string_view t = type.text;
    VrmlPrimitive primitive;  // VRML97 defaults
    primitive.type = t;
    read_fields([&](const Token& f) {
      const std::string_view n = f.text;
      if (t == "Box" && n == "size")
        primitive.size = read_vec3();
      else if (n == "radius" || n == "bottomRadius")
        primitive.radius = read_number();
      else if (n == "height")
        primitive.height = read_number();
      else if (n == "bottom")
        primitive.bottom = read_bool();
      else if (n == "side")
        primitive.side = read_bool();
      else if (n == "top")
        primitive.top = read_bool();
      else
        return false;
      return true;
    });
    if (failed_) return nullptr;
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kGeometry;
    node->geometry =
        std::make_shared<TriangleMesh>(tessellate_vrml_primitive(primitive, sink_, {path_, type.line, type.column}));
    return node;
  }

  NodePtr parse_inline(const Token& type, const std::string& def_name) {
    std::vector<std::string> urls;
    read_fields([&](const Token& f) {
      if (f.text != "url") return false;
      urls = read_strings();
      return true;
    });
    if (failed_) return nullptr;
    auto scene = std::make_shared<SceneNode>();
    scene->name = def_name;
    if (!urls.empty() && load_inline_) {
      const std::string resolved = resolve_relative(path_, urls.front());
      if (SceneTree inlined = load_inline_(resolved, {path_, type.line, type.column})) {
        scene->children.push_back(inlined);
      }
    }
    auto node = std::make_shared<VrmlNode>();
    node->kind = NodeKind::kScene;
    node->scene = scene;
    return node;
  }

  VrmlLexer lexer_;
  std::string path_;
  DiagnosticSink& sink_;
  const InlineLoader& load_inline_;
  std::map<std::string, NodePtr> defs_;
  bool failed_ = false;
  int depth_ = 0;
};

}  // namespace

std::string resolve_relative(const std::string& base_file, const std::string& url) {
  std::string p = url;
  if (p.rfind("file://", 0) == 0) p = p.substr(7);
  const std::filesystem::path path(p);
  if (path.is_absolute()) return path.lexically_normal().string();
  return (std::filesystem::path(base_file).parent_path() / path).lexically_normal().string();
}

SceneTree read_vrml(std::string_view text, const std::string& path, DiagnosticSink& sink,
                    const InlineLoader& load_inline) {
  Parser parser(text, path, sink, load_inline);
  return parser.parse_file();
}

}  // namespace bodyfmt::mesh
