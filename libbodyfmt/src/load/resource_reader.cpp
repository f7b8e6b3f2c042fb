#include "load/resource_reader.h"

#include <bodyfmt/body_keys.h>

#include <bodyfmt/read_file.h>
#include "load/body_reader.h"
#include "load/geometry.h"
#include "load/link_reader.h"
#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/scene_file.h"
#include "load/uri.h"
#include "load/values.h"
#include "mesh_import/file_cache_impl.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace bodyfmt::detail {

std::optional<std::string> read_included_file(const std::string& path, const LoadOptions& options, std::string& why) {
  if (!options.file_texts.empty()) {
    std::error_code ec;
    const std::string canonical = std::filesystem::weakly_canonical(path, ec).string();
    if (auto it = options.file_texts.find(ec ? path : canonical); it != options.file_texts.end()) return it->second;
  }
  if (options.file_cache) return options.file_cache->impl().read_text(path, options.max_file_bytes, why);
  return read_regular_file(path, options.max_file_bytes, why);
}

void note_model_text(const LoadOptions& options, const std::string& path) {
  if (options.on_model_text) options.on_model_text(path);
}

namespace {

/// Whether a YAML resource is model text: elements (a list, or a node with a type) or a library
/// of anchored nodes. Any other file a model names (a credentials file) is neither read nor
/// quoted.
bool is_model_text(const yaml::Document& doc) {
  const yaml::NodeRef& root = doc.root;
  return root && (root->is_sequence() || !doc.anchors.empty() || (root->is_mapping() && root->find("type")));
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

class Resources final : public ResourceReader {
 public:
  Resources(const LoadOptions& options, LoadContext& ctx, Model& model, LoadSession& session)
      : options_(options), ctx_(ctx), model_(model), session_(session), scenes_(options, ctx, include_depth_) {}

  void set_main_document(const yaml::Document* main_document) override { main_ = main_document; }
  bool read_yaml_without_main_document() const override { return read_yaml_without_main_; }

  void read_resource(ElementReader& reader, const yaml::NodeRef& node, const ElementFrame& frame) override {
    MappingReader r(ctx_, node, "Resource node");
    r.take({"type"});
    std::string name;
    if (auto n = r.take({"name"})) name = n->scalar();
    yaml::NodeRef uri = r.take({"uri"});
    yaml::NodeRef fragment = take_resource_node(ctx_, r);
    yaml::NodeRef metadata = r.take({"metadata"});
    ElementFrame inner = frame;
    Eigen::Affine3d X = Eigen::Affine3d::Identity();
    if (auto t = r.take({"translation"}))
      if (auto v = read_translation(ctx_, t)) X.translation() = *v;
    if (auto rot = r.take({"rotation"}))
      if (auto R = read_rotation(ctx_, rot)) X.linear() = *R;
    if (auto s = r.take({"scale"}))
      if (s->is_sequence())
        if (auto v = read_vec3(ctx_, s)) X.linear() = X.linear() * v->asDiagonal();
    // In a scene file read with a length unit, Choreonoid scales this node's translation but
    // not the file it names, which has a length unit of its own.
    if (frame.scene_file && frame.scene_length_scale != 1.0) X.linear() /= frame.scene_length_scale;
    inner = reader.push_frame(frame, X);
    r.take({"crease_angle", "creaseAngle"});
    r.report_unknown(body_key_names("element:Resource"));
    if (!uri) {
      ctx_.report("load-missing-key", node, "key \"uri\" is not found in a Resource node");
      return;
    }
    std::string path = resolve_uri(ctx_, uri, std::string(uri->scalar()), uri->location.file);
    if (path.empty()) return;
    std::string ext = lower_extension(path);
    if (ext == ".yaml" || ext == ".yml") {
      // In a scene file too: Choreonoid 25994f3e reads it there with the scene file's reader
      // (tests/data/body_choreonoid/scene_yaml_resource, made by Choreonoid itself).
      read_yaml_fragment(reader, uri, path, fragment, inner);
      return;
    }
    if (ext == ".scen") {
      MeshResource unit;
      if (metadata) read_mesh_metadata(ctx_, metadata, unit);
      scenes_.read(reader, uri.use_site(), path, unit, inner, fragment);
      return;
    }
    Shape shape;
    shape.name = name;
    shape.source = node.use_site();
    MeshResource mesh;
    mesh.uri = uri->scalar();
    mesh.uri_source = uri.use_site();
    mesh.resolved_path = path;
    if (fragment) mesh.node = fragment->scalar();
    if (metadata) read_mesh_metadata(ctx_, metadata, mesh);
    shape.geometry = mesh;
    reader.add_shape(std::move(shape), inner);
  }

  bool read_scene_geometry(ElementReader& reader, Shape& shape, const ElementFrame& frame) override {
    const MeshResource* mesh = geometry_if<MeshResource>(shape.geometry);
    if (!mesh || lower_extension(mesh->resolved_path) != ".scen") return false;
    if (!mesh->node.empty())
      ctx_.report("scene-unsupported", mesh->uri_source,
                  "bodyfmt cannot select a node of a scene file; the geometry is not read");
    else
      scenes_.read_as_geometry(reader, std::move(shape), frame);
    return true;
  }

  void read_link_node(const yaml::NodeRef& node, const std::string& type, std::vector<LinkEntry>& entries) override {
    if (type == "SubBody")
      read_subbody(node, entries);
    else
      read_continuous_track(node, entries);
  }

 private:
  const yaml::Document* load_yaml_file(const yaml::NodeRef& at, const std::string& path) {
    auto it = yaml_files_.find(path);
    if (it != yaml_files_.end()) return it->second.get();
    std::string why;
    const std::optional<std::string> text = read_included_file(path, options_, why);
    if (!text) {
      ctx_.report("resource-missing", at, "YAML resource \"" + path + "\" cannot be read: " + why);
      yaml_files_[path] = nullptr;
      return nullptr;
    }
    if (!main_) read_yaml_without_main_ = true;
    yaml::ParseOptions po;
    po.max_expanded_nodes = options_.max_expanded_yaml_nodes;
    po.max_depth = options_.max_yaml_depth;
    // body-format-spec §9.3: the resource sees the main body file's anchors.
    if (main_) po.imported_anchors = &main_->anchors;
    auto doc = yaml::parse_yaml(*text, path, po, ctx_.sink);
    if (doc && is_model_text(*doc)) note_model_text(options_, path);
    const yaml::Document* result = doc.get();
    yaml_files_[path] = std::move(doc);
    return result;
  }

  void read_yaml_fragment(ElementReader& reader, const yaml::NodeRef& uri, const std::string& path,
                          const yaml::NodeRef& fragment, const ElementFrame& frame) {
    const yaml::Document* doc = load_yaml_file(uri, path);
    if (!doc) return;
    if (!fragment && doc->root && !is_model_text(*doc)) {
      // Reported where the model names it: its own lines are not quoted, not even in a message.
      ctx_.report("load-type", uri,
                  "YAML resource \"" + std::string(uri->scalar()) +
                      "\" is not model text (neither a list of elements nor a node with a type); it is not read");
      return;
    }
    if (!fragment) {
      read_nested_yaml(reader, uri, file_identity(path), doc->root, frame);
      return;
    }
    const std::string name(fragment->scalar());
    const yaml::Node* target = nullptr;
    if (auto it = doc->anchors.find(name); it != doc->anchors.end())
      target = it->second;
    else if (main_) {
      if (auto m = main_->anchors.find(name); m != main_->anchors.end()) target = m->second;
    }
    if (!target) {
      ctx_.report("resource-fragment", fragment,
                  "fragment \"" + name + "\" is not found in \"" + std::string(uri->scalar()) + "\"");
      return;
    }
    // The fragment is used like an alias: its findings point into the library file and name
    // the Resource node's `node:` as the use site.
    yaml::NodeRef ref;
    ref.node = target;
    ref.alias_site = &fragment.use_site();
    read_nested_yaml(reader, fragment, file_identity(path) + "#" + name, ref, frame);
  }

  /// Reads YAML resource text that may name YAML resources in turn, which Choreonoid follows
  /// without a guard: a cycle, or a chain deeper than one document may be, is refused at `at`.
  void read_nested_yaml(ElementReader& reader, const yaml::NodeRef& at, const std::string& key,
                        const yaml::NodeRef& elements, const ElementFrame& frame) {
    if (std::find(yaml_chain_.begin(), yaml_chain_.end(), key) != yaml_chain_.end()) {
      ctx_.report("resource-recursion", at,
                  "YAML resources include each other: " + include_chain_text(yaml_chain_, key));
      return;
    }
    const int depth = elements->expanded_depth;
    if (include_depth_ + depth > options_.max_yaml_depth) {
      ctx_.report("resource-recursion", at,
                  "resources nested in one another are deeper than " + std::to_string(options_.max_yaml_depth) +
                      " YAML levels together; this one is not read");
      return;
    }
    yaml_chain_.push_back(key);
    include_depth_ += depth;
    // The fragment is one node (or a list of them), as a scene file's `scene` is: in a scene
    // file, a mapping with a type is that node, not an elements mapping keyed by type.
    ElementFrame top = frame;
    top.scene_top = frame.scene_file;
    reader.read_elements(elements, top);
    include_depth_ -= depth;
    yaml_chain_.pop_back();
  }

  std::shared_ptr<const Model> load_subbody(const yaml::NodeRef& uri, const std::string& path) {
    const std::string canonical = file_identity(path);
    if (std::find(session_.chain.begin(), session_.chain.end(), canonical) != session_.chain.end()) {
      ctx_.report("subbody-recursion", uri,
                  "recursive sub-body include: " + include_chain_text(session_.chain, canonical));
      return nullptr;
    }
    if (auto it = session_.subbodies.find(canonical); it != session_.subbodies.end()) return it->second;
    std::shared_ptr<const Model> result;
    std::string why;
    const std::optional<std::string> text = read_included_file(path, options_, why);
    if (!text) {
      ctx_.report("subbody-missing", uri,
                  "sub-body \"" + std::string(uri->scalar()) + "\" cannot be read at \"" + path + "\": " + why);
    } else {
      BodyReader reader(options_, ctx_.sink, session_);
      if (auto model = reader.read(*text, path, false))
        result = std::make_shared<const Model>(std::move(*model));
      else
        ctx_.report("subbody-load", uri, "the sub-body \"" + std::string(uri->scalar()) + "\" cannot be loaded");
    }
    session_.subbodies[canonical] = result;
    return result;
  }

  void read_subbody(const yaml::NodeRef& node, std::vector<LinkEntry>& entries) {
    MappingReader r(ctx_, node, "SubBody node");
    r.take({"type"});
    yaml::NodeRef uri = r.take({"uri"});
    if (!uri) {
      ctx_.report("load-missing-key", node, "uri must be specified for a SubBody");
      return;
    }
    std::string path = resolve_uri(ctx_, uri, std::string(uri->scalar()), uri->location.file);
    if (path.empty()) return;
    std::shared_ptr<const Model> sub = load_subbody(uri, path);
    if (!sub || sub->links.empty()) return;
    auto text = [&](KeyNames names) {
      yaml::NodeRef v = r.take(names);
      return v && v->is_scalar() ? std::optional<std::string>(v->scalar()) : std::nullopt;
    };
    const std::string prefix = text({"prefix"}).value_or("");
    const std::string suffix = text({"suffix"}).value_or("");
    const std::string device_prefix = text({"device_prefix", "devicePrefix"}).value_or(prefix);
    int id_offset = 0;
    if (auto v = r.take({"joint_id_offset", "jointIdOffset"}))
      id_offset = static_cast<int>(optional_int(ctx_, v).value_or(0));  // a whole read, default 0
    yaml::NodeRef parent = r.take({"parent"});
    r.take({"name"});

    const LinkIndex base = static_cast<LinkIndex>(model_.links.size());
    const MeshIndex mesh_base = static_cast<MeshIndex>(model_.meshes.size());
    for (std::size_t i = 0; i < sub->links.size(); ++i) {
      Link link = sub->links[i];
      link.name = prefix + link.name + suffix;
      if (!link.joint_name.empty()) link.joint_name = prefix + link.joint_name + suffix;
      if (link.joint_id >= 0) link.joint_id += id_offset;
      for (Shape& shape : link.shapes)
        if (auto* mesh = geometry_if<MeshResource>(shape.geometry); mesh && mesh->mesh >= 0) mesh->mesh += mesh_base;
      LinkEntry entry;
      if (link.parent >= 0) {
        entry.parent_name = prefix + sub->links[static_cast<std::size_t>(link.parent)].name + suffix;
      } else if (parent) {
        entry.parent_name = parent->scalar();
        entry.parent_site = parent.use_site();
      }
      link.parent = -1;
      link.children.clear();
      model_.links.push_back(std::move(link));
      entries.push_back(entry);
    }
    for (const MeshAsset& asset : sub->meshes) model_.meshes.push_back(asset);
    for (Device device : sub->devices) {
      device.name = device_prefix + device.name;
      device.link += base;
      model_.devices.push_back(std::move(device));
    }
    for (ExtraJoint joint : sub->extra_joints) {
      joint.link1 += base;
      joint.link2 += base;
      model_.extra_joints.push_back(joint);
    }
    apply_subbody_overrides(ctx_, r, model_, base, this);
    r.report_unknown(body_key_names("link:SubBody"));
  }

  void read_continuous_track(const yaml::NodeRef& node, std::vector<LinkEntry>& entries) {
    // body-format-spec §11.1: a template link expanded into a chain NAME0..NAME(n-1).
    const yaml::MapEntry* num = node->find("numJoints");
    const yaml::MapEntry* offset = node->find("joint_offset");
    if (!offset) offset = node->find("jointOffset");
    const yaml::MapEntry* angles = node->find("initialJointAngles");
    if (!node->find("parent")) ctx_.report("load-missing-key", node, "parent must be specified for a ContinuousTrack");
    if (!num) {
      ctx_.report("load-missing-key", node, "numJoints must be specified for a ContinuousTrack");
      return;
    }
    const long n = required_int(ctx_, num->value).value_or(0);
    if (n < 3) {
      ctx_.report("load-continuous-track", num->value, "numJoints must be more than 2");
      return;
    }
    if (!offset) {
      ctx_.report("load-missing-key", node, "jointOffset must be specified for a ContinuousTrack");
      return;
    }
    auto joint_offset = read_vec3(ctx_, offset->value);
    if (!joint_offset) return;
    std::vector<double> initial;
    if (angles) initial = read_numbers(ctx_, angles->value).value_or(std::vector<double>{});

    LinkEntry first =
        read_link(ctx_, node, model_, this, {"numJoints", "joint_offset", "jointOffset", "initialJointAngles"});
    const LinkIndex t = static_cast<LinkIndex>(model_.links.size()) - 1;
    const Link templ = model_.links[static_cast<std::size_t>(t)];
    const std::string base = templ.name;
    Link& first_link = model_.links[static_cast<std::size_t>(t)];
    first_link.name = base + "0";
    first_link.joint_type = JointType::kFree;
    // addTrackLink sets the first link's initial angle to 0 and each next one's from
    // initialJointAngles: the node's own joint_angle / joint_displacement reaches no link.
    first_link.initial_displacement = 0;
    for (std::string_view key : {"joint_displacement", "jointDisplacement", "joint_angle", "jointAngle"}) {
      const yaml::MapEntry* e = node->find(key);
      if (!e || templ.initial_displacement == 0) continue;
      ctx_.report("load-ignored-value", node.child(e->value),
                  "Choreonoid starts the first link of a ContinuousTrack at 0 and the next ones at "
                  "initialJointAngles: this value reaches no link",
                  "write the angles in initialJointAngles");
      break;
    }
    // readLinkContents registered the node's name before addTrackLink renamed the link.
    if (!base.empty()) {
      first.alias = base;
      first.alias_site = templ.sources.name();
    }
    // The next links are clones: they keep the template's joint_name and joint_id, which
    // Choreonoid neither checks nor changes there.
    for (std::string_view key : {"joint_name", "joint_id", "jointId"}) {
      const yaml::MapEntry* e = node->find(key);
      if (!e || (key == "joint_name" ? templ.joint_name.empty() : templ.joint_id < 0)) continue;
      ctx_.report("load-track-shared-joint", node.child(e->value),
                  std::string("all ") + std::to_string(n) + " links of this ContinuousTrack have this " +
                      (key == "joint_name" ? "joint name" : "joint id") +
                      (key == "joint_name" ? "" : "; Choreonoid's joint list holds the first link only"),
                  std::string("remove ") + std::string(key) + " from the ContinuousTrack node");
    }
    entries.push_back(first);
    for (long i = 1; i < n; ++i) {
      Link link = templ;
      link.name = base + std::to_string(i);
      link.joint_type = JointType::kRevolute;
      // Choreonoid clones the template link and sets only the translation of the clone's
      // offset (Link::setOffsetTranslation): the template's rotation stays in every link.
      link.X_PL.translation() = *joint_offset;
      link.initial_displacement =
          static_cast<std::size_t>(i - 1) < initial.size()
              ? ctx_.angle(initial[static_cast<std::size_t>(i - 1)],
                           angles->value.child(angles->value->items()[static_cast<std::size_t>(i - 1)]))
              : 0.0;
      model_.links.push_back(std::move(link));
      LinkEntry entry;
      entry.parent_name = base + std::to_string(i - 1);
      entries.push_back(entry);
    }
  }

  const LoadOptions& options_;
  LoadContext& ctx_;
  Model& model_;
  const yaml::Document* main_ = nullptr;
  bool read_yaml_without_main_ = false;
  LoadSession& session_;
  std::map<std::string, std::unique_ptr<yaml::Document>> yaml_files_;
  std::vector<std::string> yaml_chain_;  ///< "file#fragment" of the YAML resources being read, outermost first
  /// The depths of the YAML resources and scene files being read, one inside the next, added up.
  int include_depth_ = 0;
  SceneFiles scenes_;
};

}  // namespace

std::unique_ptr<ResourceReader> make_resource_handler(const LoadOptions& options, LoadContext& ctx, Model& model,
                                                      LoadSession& session) {
  return std::make_unique<Resources>(options, ctx, model, session);
}

}  // namespace bodyfmt::detail
