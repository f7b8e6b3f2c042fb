#include "page.h"

#include <bodyfmt/geometry_fix.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/inertia.h>
#include <bodyfmt/pose.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/text.h>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>

#ifndef BODYVIEW_ASSETS_FROM_BINDIR
#define BODYVIEW_ASSETS_FROM_BINDIR "../share/bodyfmt/bodyview"
#endif
#ifndef BODYVIEW_ASSETS_BUILD_DIR
#define BODYVIEW_ASSETS_BUILD_DIR ""
#endif

namespace bodyfmt::bodyview {
namespace {

namespace fs = std::filesystem;

std::string number(double v) {
  if (!std::isfinite(v) || std::abs(v) >= kUnlimited) return "null";
  return fmt::format("{:.17g}", v);
}

template <typename Vector>
std::string numbers(const Vector& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? "," : "") + number(v(i));
  return out + "]";
}

/// 16 numbers, column-major (three.js Matrix4.fromArray, WebGL).
std::string matrix(const Eigen::Matrix4d& M) {
  std::string out = "[";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out += (c || r ? "," : "") + number(M(r, c));
  return out + "]";
}

std::string row_major(const Eigen::Matrix3d& M) {
  std::string out = "[";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out += (c || r ? "," : "") + number(M(r, c));
  return out + "]";
}

std::string where(const SourceLocation& at) {
  if (at.file.empty()) return "";
  return at.known() ? fmt::format("{}:{}", at.file.str(), at.line) : at.file.str();
}

std::string box(const BoundingBox& b) {
  if (b.empty()) return "null";
  return "[" + number(b.min.x()) + "," + number(b.min.y()) + "," + number(b.min.z()) + "," + number(b.max.x()) + "," +
         number(b.max.y()) + "," + number(b.max.z()) + "]";
}

/// The box of uniform density with the link's mass and principal moments (edges along the
/// principal axes, centred at the centre of mass), or null when it has none.
std::string inertia_box(const MassProperties& mass) {
  if (!(mass.mass > 0) || !computable(mass)) return "null";
  const PrincipalInertia p = principal_inertia(mass.inertia);
  const Eigen::Vector3d& I = p.moments;
  Eigen::Vector3d size;
  for (int k = 0; k < 3; ++k) size(k) = std::sqrt(std::max(0.0, 6.0 * (I.sum() - 2.0 * I(k)) / mass.mass));
  Eigen::Matrix4d X = Eigen::Matrix4d::Identity();
  X.topLeftCorner<3, 3>() = p.axes;
  if (X.topLeftCorner<3, 3>().determinant() < 0) X.col(2).head<3>() *= -1;  // a rotation, not a mirror
  X.col(3).head<3>() = mass.center_of_mass;
  return "{\"size\":" + numbers(size) + ",\"X\":" + matrix(X) + "}";
}

/// The link's mass properties with its shapes' tensor at its written mass (what `bodycheck
/// --fix=geometry` computes), their inertia box beside the written one's, and the centre of mass
/// and inertia the fix writes where bodycheck offers it (`fix`). Each RigidBody element's shapes
/// are at its own mass (the shapes below it are what it stands for); a link whose mass only
/// RigidBody elements carry has no link-level fix-it to show. null where the link has no solid shape or no mass. A
/// shape that is no solid is left out and counted.
std::string geometry_json(const Model& model, const Link& link, double total_mass, bool offered) {
  CollectingSink ignored;  // a shape that is no solid is counted in left_out
  const LinkGeometryMass geometry = link_geometry_mass(model, link, ignored);
  const std::optional<GeometryAtWrittenMass> at = geometry_at_written_mass(link, geometry);
  const std::optional<MassProperties> combined =
      at ? std::optional<MassProperties>(at->combined) : geometry_at_mass(geometry, total_mass);
  if (!combined || !(combined->mass > 0)) return "null";
  std::string fix = ",\"fix\":false,\"fix_center_of_mass\":null,\"fix_inertia\":null";
  if (at && at->link_keys) {
    const MassProperties keys = written_mass_keys(*at->link_keys);
    fix = ",\"fix\":" + std::string(offered ? "true" : "false") +
          ",\"fix_center_of_mass\":" + numbers(keys.center_of_mass) + ",\"fix_inertia\":" + row_major(keys.inertia);
  }
  return "{\"from\":" + std::string(geometry.from_visual ? "\"visual\"" : "\"collision\"") +
         ",\"solids\":" + std::to_string(geometry.solids + geometry.solids_in_rigid_bodies()) +
         ",\"left_out\":" + std::to_string(geometry.left_out) + ",\"mass\":" + number(combined->mass) +
         ",\"com\":" + numbers(combined->center_of_mass) + ",\"inertia\":" + row_major(combined->inertia) +
         ",\"inertia_box\":" + inertia_box(*combined) + fix + "}";
}

std::string devices_json(const Model& model) {
  std::string out = "[";
  for (std::size_t i = 0; i < model.devices.size(); ++i) {
    const Device& d = model.devices[i];
    out += (i ? ",\n" : "\n") + std::string("{\"name\":") + text::json_quote(d.name) +
           ",\"type\":" + text::json_quote(d.type) + ",\"link\":" + std::to_string(d.link) +
           ",\"X\":" + matrix(d.X_LD.matrix()) + ",\"source\":" + text::json_quote(where(d.source));
    if (const auto* camera = std::get_if<CameraParams>(&d.params)) {
      out += ",\"camera\":{\"fov\":" + number(camera->field_of_view) +
             ",\"near\":" + number(camera->near_clip_distance) + ",\"far\":" + number(camera->far_clip_distance) +
             ",\"aspect\":" + number(camera->height > 0 ? double(camera->width) / camera->height : 1.0) + "}";
    } else if (const auto* light = std::get_if<LightParams>(&d.params)) {
      out += ",\"light\":{\"color\":" + numbers(light->color) + ",\"direction\":" + numbers(light->direction) +
             ",\"spot\":" + (d.type == "SpotLight" ? "true" : "false") + "}";
    }
    out += "}";
  }
  return out + "]";
}

/// The link a finding is about: in the finding's file, the last link written at or before it.
int link_of(const Model& model, const SourceLocation& at) {
  int best = -1, best_line = 0;
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const SourceLocation& s = model.links[i].source;
    if (s.file == at.file && s.line <= at.line && s.line >= best_line) {
      best = static_cast<int>(i);
      best_line = s.line;
    }
  }
  return best;
}

/// A finding's place as the list shows it: the file's name (not its folders, which would push
/// line:col out of the narrow side bar) with line and column.
std::string short_where(const SourceLocation& at) {
  const std::string name = std::filesystem::path(at.file.str()).filename().string();
  return at.known() ? fmt::format("{}:{}:{}", name, at.line, at.column) : name;
}

std::string findings_json(const PageInput& input) {
  std::string out = "[";
  TextOptions plain;
  plain.color = false;
  for (std::size_t i = 0; i < input.findings.size(); ++i) {
    const Diagnostic& d = input.findings[i];
    const SourceLocation& at = d.location;
    out += (i ? ",\n" : "\n") + std::string("{\"severity\":") + text::json_quote(severity_name(d.severity)) +
           ",\"rule\":" + text::json_quote(d.rule_id) + ",\"message\":" + text::json_quote(d.message) + ",\"where\":" +
           text::json_quote(at.known() ? fmt::format("{}:{}:{}", at.file.str(), at.line, at.column) : at.file.str()) +
           ",\"at\":" + text::json_quote(short_where(at)) + ",\"text\":" +
           text::json_quote(input.sources ? format_text_diagnostic(d, *input.sources, plain) : d.message) +
           ",\"link\":" + std::to_string(input.model ? link_of(*input.model, at) : -1) + "}";
  }
  return out + "]";
}

// The viewer's files and three.js's modules: a few MB together (three.module.js is the largest,
// about 1.2 MB), read through the one bounded reader so that a replaced asset folder cannot
// hand the page a device or an endless file.
constexpr std::uintmax_t kMaxAssetBytes = 64u << 20;

std::optional<std::string> read_text(const fs::path& path, std::string& why) {
  return read_regular_file(path.string(), kMaxAssetBytes, why);
}

std::string base64(std::string_view bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8 | (unsigned char)bytes[i + 2];
    out += table[v >> 18 & 63], out += table[v >> 12 & 63], out += table[v >> 6 & 63], out += table[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = (unsigned char)bytes[i] << 16;
    out += table[v >> 18 & 63], out += table[v >> 12 & 63], out += "==";
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8;
    out += table[v >> 18 & 63], out += table[v >> 12 & 63], out += table[v >> 6 & 63], out += '=';
  }
  return out;
}

/// JSON inside a <script> element, with no character the HTML tokenizer reads there: "<" (which
/// begins "</script" and the "<!--" that makes a later "</script>" not end the element), ">" (of
/// "-->"), "&", and U+2028/U+2029, as JSON escapes. They can only occur inside JSON strings, so
/// the JSON means the same, whatever text the model carries.
std::string json_for_script(std::string_view json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<')
      out += "\\u003c";
    else if (c == '>')
      out += "\\u003e";
    else if (c == '&')
      out += "\\u0026";
    else if (json.compare(i, 3, "\xE2\x80\xA8") == 0 || json.compare(i, 3, "\xE2\x80\xA9") == 0) {
      out += json[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

/// The viewer's script inside a <script> element: "</" would end the element, and "<\/" means
/// the same in its strings and regular expressions.
std::string script_safe(std::string json) {
  for (std::size_t at = 0; (at = json.find("</", at)) != std::string::npos; at += 3) json.replace(at, 2, "<\\/");
  return json;
}

// The three.js modules the viewer imports, in dependency order (the page links them by name).
constexpr std::array<const char*, 6> kModules = {"three.core.js",    "three.module.js", "BufferGeometryUtils.js",
                                                 "SkeletonUtils.js", "GLTFLoader.js",   "OrbitControls.js"};

}  // namespace

fs::path find_assets(const char* argv0) {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec && argv0) exe = fs::absolute(argv0, ec);
  const fs::path installed = exe.parent_path() / BODYVIEW_ASSETS_FROM_BINDIR;
  if (fs::is_regular_file(installed / "viewer.js", ec)) return installed;
  const fs::path built = BODYVIEW_ASSETS_BUILD_DIR;
  if (!built.empty() && fs::is_regular_file(built / "viewer.js", ec)) return built;
  return {};
}

std::string page_data_json(const PageInput& input) {
  const Model& model = *input.model;
  const Derived& derived = *input.derived;
  std::string out = "{\"model\":" + text::json_quote(model.name) + ",\"file\":" + text::json_quote(model.source_file) +
                    ",\"total_mass\":" + number(derived.total_mass) +
                    ",\"serve\":" + text::json_quote(input.serve_status_url) + ",\"links\":[";
  const std::vector<bool> offered = links_for_geometry_fix(model, input.findings);
  for (std::size_t i = 0; i < model.links.size(); ++i) {
    const Link& l = model.links[i];
    const MassProperties& m = derived.mass[i];
    const bool movable = is_one_dof(l);
    out += (i ? ",\n" : "\n") + std::string("{\"name\":") + text::json_quote(l.name) +
           ",\"parent\":" + std::to_string(l.parent) + ",\"joint\":" + text::json_quote(joint_name_of(l)) +
           ",\"type\":" + text::json_quote(joint_type_name(l.joint_type)) + ",\"axis\":" + numbers(l.joint_axis) +
           ",\"lower\":" + (movable ? number(l.joint_range_lower) : "null") +
           ",\"upper\":" + (movable ? number(l.joint_range_upper) : "null") +
           ",\"q0\":" + (movable ? number(l.initial_displacement) : "0") +
           ",\"X_PL\":" + matrix(as_isometry(l.X_PL).matrix()) + ",\"mass\":" + number(m.mass) +
           ",\"com\":" + numbers(m.center_of_mass) + ",\"inertia\":" + row_major(m.inertia) +
           ",\"inertia_box\":" + inertia_box(m) + ",\"geometry\":" + geometry_json(model, l, m.mass, offered[i]) +
           ",\"source\":" + text::json_quote(where(l.source)) +
           ",\"mass_source\":" + text::json_quote(where(source_of(l, LinkSources::kMass))) +
           ",\"inertia_source\":" + text::json_quote(where(inertia_source(l))) +
           ",\"visual_box\":" + box(derived.bounds[i].visual) +
           ",\"collision_box\":" + box(derived.bounds[i].collision) + "}";
  }
  out += "],\n\"devices\":" + devices_json(model) + ",\n\"findings\":" + findings_json(input) + "}";
  return out;
}

std::optional<std::string> build_page(const fs::path& assets, const PageInput& input, std::string& error) {
  std::string why;
  std::optional<std::string> page, script, style;
  for (auto [file, text] : {std::pair{"viewer.html", &page}, {"viewer.js", &script}, {"viewer.css", &style}}) {
    *text = read_text(assets / file, why);
    if (!*text) {
      error = "cannot read the viewer's " + std::string(file) + " in " + assets.string() + ": " + why;
      return std::nullopt;
    }
  }
  std::string modules;
  for (const char* name : kModules) {
    auto text = read_text(assets / "three" / name, why);
    if (!text) {
      error = "cannot read three.js's " + std::string(name) + " in " + (assets / "three").string() + ": " + why;
      return std::nullopt;
    }
    modules += "<script type=\"text/plain\" class=\"bv-module\" data-name=\"" + std::string(name) + "\">" +
               base64(*text) + "</script>\n";
  }
  // The template's markers in page order; the text put in is never searched again.
  const std::pair<std::string_view, std::string> parts[] = {{"/*@STYLE@*/", *style},
                                                            {"@DATA@", json_for_script(page_data_json(input))},
                                                            {"@GLB@", base64(input.glb)},
                                                            {"<!--@MODULES@-->", modules},
                                                            {"/*@SCRIPT@*/", script_safe(*script)}};
  std::string html;
  std::size_t from = 0;
  for (const auto& [marker, text] : parts) {
    const std::size_t at = page->find(marker, from);
    if (at == std::string::npos) {
      error = "viewer.html has no " + std::string(marker);
      return std::nullopt;
    }
    html.append(*page, from, at - from).append(text);
    from = at + marker.size();
  }
  html.append(*page, from, std::string::npos);
  page = std::move(html);
  return page;
}

}  // namespace bodyfmt::bodyview
