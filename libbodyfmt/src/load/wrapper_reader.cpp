#include "load/wrapper_reader.h"

#include "load/body_reader.h"
#include "load/geometry.h"
#include "load/mapping_reader.h"
#include "load/resource_reader.h"
#include "load/scalar.h"
#include "load/uri.h"
#include "text/text_util.h"

#include <bodyfmt/tessellate.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace bodyfmt::detail {
namespace {

namespace fs = std::filesystem;

// Choreonoid's StdBodyLoader::loadAnotherFormatBodyFile reads these; the rest of the mapping
// becomes the body's info (body-format-spec §2.3, §2.4).
const std::vector<std::string_view> kWrapperKeys = {"model_file", "linkInfo", "geometry", "body_handlers"};

// Header keys of a body file that a wrapper does not read: its model comes from model_file.
const std::vector<std::string_view> kBodyOnlyKeys = {"format_version", "formatVersion", "angle_unit", "angleUnit",
                                                     "name",           "root_link",     "rootLink",   "links",
                                                     "extra_joints",   "extraJoints"};

// Link keys of a .body file. Under linkInfo they only enter the link's info mapping: the loader
// does not read them back into the link, so they change neither its mass nor its joint.
// (rotorInertia is left out: Choreonoid's AGX simulator reads it from the link's info.)
const std::vector<std::string_view> kLinkPropertyKeys = {"name",
                                                         "parent",
                                                         "joint_name",
                                                         "jointName",
                                                         "translation",
                                                         "rotation",
                                                         "joint_type",
                                                         "jointType",
                                                         "joint_axis",
                                                         "jointAxis",
                                                         "joint_id",
                                                         "jointId",
                                                         "actuation_mode",
                                                         "actuationMode",
                                                         "joint_angle",
                                                         "jointAngle",
                                                         "joint_displacement",
                                                         "jointDisplacement",
                                                         "joint_range",
                                                         "jointRange",
                                                         "max_joint_velocity",
                                                         "maxJointVelocity",
                                                         "joint_velocity_range",
                                                         "jointVelocityRange",
                                                         "max_joint_effort",
                                                         "joint_axis_inertia",
                                                         "rotor_inertia",
                                                         "gear_ratio",
                                                         "gearRatio",
                                                         "center_of_mass",
                                                         "centerOfMass",
                                                         "mass",
                                                         "inertia",
                                                         "material",
                                                         "elements"};

// Formats Choreonoid reads through plugins or loaders bodyfmt does not have.
std::string format_name(const std::string& extension) {
  if (extension == ".wrl") return "an OpenHRP VRML body model";
  if (extension == ".xacro") return "a xacro macro file (expand it to a .urdf with xacro first)";
  if (extension == ".sdf" || extension == ".world") return "an SDFormat model";
  if (extension == ".urdf") return "a URDF model";
  return "";
}

// Nesting of wrappers and sub-bodies beyond this is refused: each level is a reader on the stack.
constexpr std::size_t kMaxNesting = 64;

class WrapperReader {
 public:
  WrapperReader(const LoadOptions& options, LoadContext& ctx, LoadSession& session, const std::string& file_name)
      : options_(options), ctx_(ctx), session_(session), file_name_(file_name) {}

  std::optional<Model> read(const yaml::NodeRef& root) {
    MappingReader r(ctx_, root, "wrapper body file");
    const yaml::NodeRef model_file = r.take({"model_file", "modelFile"});
    const yaml::NodeRef geometry = r.take({"geometry"});
    const yaml::NodeRef link_info = r.take({"linkInfo"});
    const yaml::NodeRef handlers = r.take({"body_handlers"});
    for (std::string_view key : kBodyOnlyKeys) {
      if (const yaml::MapEntry* entry = root->find(key)) {
        r.ignore(key);
        ctx_.report("load-ignored-key", entry->key_location,
                    "\"" + std::string(key) +
                        "\" has no effect in a wrapper body file: its model is read from "
                        "model_file, and Choreonoid keeps this key as body info",
                    "write it in the model file, or add format: ChoreonoidBody if this is the model");
      }
    }
    for (std::string_view key : known_body_info_keys()) r.ignore(key);
    r.report_unknown(kWrapperKeys);

    std::optional<int> division_number;
    if (geometry && !read_geometry(geometry, division_number)) return std::nullopt;
    std::optional<Model> model = read_model_file(model_file, division_number);
    if (!model) return std::nullopt;
    model->source_file = file_name_;
    model->source = root->location;
    if (handlers) {
      if (handlers->is_scalar())
        model->body_handlers.emplace_back(handlers->scalar());
      else if (handlers->is_sequence())
        for (const auto& h : handlers->items())
          if (h->is_scalar()) model->body_handlers.emplace_back(h->scalar());
    }
    if (link_info) apply_link_info(link_info, *model);
    return model;
  }

 private:
  /// `geometry: {divisionNumber: N}`: the division number of every primitive the model file
  /// does not give one. Choreonoid refuses a geometry value that is not a mapping.
  bool read_geometry(const yaml::NodeRef& geometry, std::optional<int>& division_number) {
    if (!geometry->is_mapping()) {
      ctx_.report("load-wrapper", geometry, "the geometry of a wrapper body file must be a mapping",
                  "write geometry: {divisionNumber: N}");
      return false;
    }
    MappingReader g(ctx_, geometry, "wrapper geometry");
    if (const yaml::NodeRef n = g.take({"divisionNumber"})) {
      const std::optional<long> value = required_int(ctx_, n);
      if (!value) return false;  // Choreonoid refuses the file
      division_number = division_number_from(ctx_, n, *value, "divisionNumber");
    }
    g.report_unknown({"divisionNumber"});
    return true;
  }

  std::optional<Model> read_model_file(const yaml::NodeRef& model_file, std::optional<int> division_number) {
    if (!model_file->is_scalar() || model_file->scalar().empty()) {
      ctx_.report("load-wrapper", model_file, "model_file must name the model's file");
      return std::nullopt;
    }
    const std::string written(model_file->scalar());
    if (written.find("://") != std::string::npos) {
      ctx_.report("wrapper-format", model_file,
                  "model_file \"" + written + "\" is read as a file path: Choreonoid resolves no URI scheme here",
                  "write the path relative to this file");
      return std::nullopt;
    }
    // Choreonoid: relative to the wrapper's folder unless it has a root.
    fs::path path(written);
    if (!path.has_root_path()) path = fs::path(file_name_).parent_path() / path;
    const std::string resolved = path.lexically_normal().string();
    // Choreonoid picks the loader by the extension as written (case-sensitive).
    const std::string extension = path.extension().string();
    const bool body_format = extension == ".body" || extension == ".yaml" || extension == ".yml";
    const auto reader = options_.model_file_readers.find(extension);
    if (!body_format && reader == options_.model_file_readers.end()) {
      report_unsupported(model_file, extension);
      return std::nullopt;
    }
    const std::string identity = file_identity(resolved);
    if (std::find(session_.chain.begin(), session_.chain.end(), identity) != session_.chain.end()) {
      ctx_.report("wrapper-recursion", model_file,
                  "the wrapper includes itself: " + include_chain_text(session_.chain, identity));
      return std::nullopt;
    }
    if (session_.chain.size() >= kMaxNesting) {
      ctx_.report("wrapper-recursion", model_file,
                  "model files nest more than " + std::to_string(kMaxNesting) +
                      " levels deep: " + include_chain_text(session_.chain, identity));
      return std::nullopt;
    }
    std::string why;
    const std::optional<std::string> text = read_included_file(resolved, options_, why);
    if (!text) {
      ctx_.report("wrapper-missing", model_file,
                  "model_file \"" + written + "\" cannot be read at \"" + resolved + "\": " + why);
      return std::nullopt;
    }
    std::optional<Model> model;
    if (body_format) {
      model = read_body_model(*text, resolved, division_number);
    } else {
      model = reader->second(resolved, *text, options_, ctx_.sink);
      // Formats without per-shape division numbers: the wrapper's applies to every shape.
      if (model && division_number)
        for (Link& link : model->links)
          for (Shape& shape : link.shapes) shape.division_number = *division_number;
      // Choreonoid's other loaders name the body instance, not the model: the model keeps the
      // wrapper's file name.
      if (model) model->name = fs::path(file_name_).stem().string();
    }
    if (!model) {
      ctx_.report("load-wrapper", model_file, "the model \"" + written + "\" named in model_file cannot be loaded");
      return std::nullopt;
    }
    if (model->links.empty()) {
      ctx_.report("load-wrapper", model_file, "the model \"" + written + "\" named in model_file has no link");
      return std::nullopt;
    }
    return model;
  }

  std::optional<Model> read_body_model(const std::string& text, const std::string& path,
                                       std::optional<int> division_number) {
    // Choreonoid loads it into the same body: the model keeps the wrapper's file name unless
    // the file sets `name`, and its primitives take the wrapper's division number.
    struct Restore {
      LoadSession& session;
      int division_number;
      std::string name;
      ~Restore() {
        session.default_division_number = division_number;
        session.default_model_name = name;
      }
    } restore{session_, session_.default_division_number, session_.default_model_name};
    if (division_number) session_.default_division_number = *division_number;
    session_.default_model_name = fs::path(file_name_).stem().string();
    BodyReader reader(options_, ctx_.sink, session_);
    return reader.read(text, path, false);
  }

  void report_unsupported(const yaml::NodeRef& model_file, const std::string& extension) {
    std::string lower = extension;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool readable =
        lower == ".body" || lower == ".yaml" || lower == ".yml" || options_.model_file_readers.count(lower) > 0;
    if (readable && lower != extension) {
      ctx_.report("wrapper-format", model_file,
                  "Choreonoid matches model_file's extension \"" + extension +
                      "\" case-sensitively and reads no "
                      "such format",
                  "rename the file to end in \"" + lower + "\"");
      return;
    }
    const std::string what = format_name(lower);
    std::string message = extension.empty() ? "model_file has no extension, which selects a model format"
                                            : "bodyfmt cannot read the model_file format \"" + extension + "\"";
    if (!what.empty()) message += " (" + what + ")";
    std::string hint = "bodyfmt reads model files ending in .body, .yaml, .yml";
    for (const auto& [known, reader] : options_.model_file_readers) hint += ", " + known;
    if (lower == ".urdf")
      hint =
          "this program installs no URDF reader (LoadOptions::model_file_readers); the "
          "bodyfmt tools do";
    ctx_.report("wrapper-format", model_file, std::move(message), std::move(hint));
  }

  /// `linkInfo: {LINK: {key: value}}`: Choreonoid inserts each mapping into the named link's
  /// info, where simulators read their own parameters; nothing of the link itself changes. The
  /// model keeps no info, so only what would be misread is reported.
  void apply_link_info(const yaml::NodeRef& link_info, const Model& model) {
    if (!link_info->is_mapping()) {
      ctx_.report("load-ignored-value", link_info, "linkInfo must be a mapping of link names; Choreonoid ignores it");
      return;
    }
    std::vector<std::string_view> names;
    for (const Link& link : model.links) names.push_back(link.name);
    std::sort(names.begin(), names.end());
    for (const yaml::MapEntry& entry : link_info->entries()) {
      const yaml::NodeRef value = link_info.child(entry.value);
      const LinkIndex link = model.find_link(entry.key);
      if (link < 0) {
        const std::string_view guess = text::suggest(entry.key, names);
        ctx_.report("wrapper-link-info", entry.key_location,
                    "linkInfo names link \"" + std::string(entry.key) +
                        "\", which the model has not; Choreonoid "
                        "ignores its info",
                    guess.empty() ? std::string() : "did you mean \"" + std::string(guess) + "\"?");
        continue;
      }
      if (!value->is_mapping()) {
        ctx_.report("load-ignored-value", value,
                    "the linkInfo of link \"" + std::string(entry.key) + "\" must be a mapping; Choreonoid ignores it");
        continue;
      }
      for (const yaml::MapEntry& key : value->entries()) {
        if (std::find(kLinkPropertyKeys.begin(), kLinkPropertyKeys.end(), key.key) != kLinkPropertyKeys.end()) {
          ctx_.report("load-ignored-key", key.key_location,
                      "linkInfo key \"" + std::string(key.key) + "\" does not change link \"" + std::string(entry.key) +
                          "\": Choreonoid only adds it to the link's info",
                      "set it in the model file");
        } else {
          ctx_.report("load-info-key", key.key_location,
                      "linkInfo key \"" + std::string(key.key) + "\" is kept as info of link \"" +
                          std::string(entry.key) + "\" (simulators read their parameters there)");
        }
      }
    }
  }

  const LoadOptions& options_;
  LoadContext& ctx_;
  LoadSession& session_;
  const std::string& file_name_;
};

}  // namespace

bool is_wrapper(const yaml::Node& root) {
  return root.is_mapping() && !root.find("format") && (root.find("model_file") || root.find("modelFile"));
}

std::optional<Model> read_wrapper(const LoadOptions& options, LoadContext& ctx, LoadSession& session,
                                  const yaml::NodeRef& root, const std::string& file_name) {
  return WrapperReader(options, ctx, session, file_name).read(root);
}

}  // namespace bodyfmt::detail
