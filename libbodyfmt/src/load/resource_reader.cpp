#include "load/resource_reader.h"

#include "load/geometry.h"
#include "load/mapping_reader.h"
#include "load/scalar.h"
#include "load/values.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace bodyfmt::detail {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

class Resources final : public ResourceReader {
 public:
  Resources(const LoadOptions& options, LoadContext& ctx, Model& model, const yaml::Document* main)
      : options_(options), ctx_(ctx), model_(model), main_(main) {}

  void read_resource(ElementReader& reader, const yaml::NodeRef& node, const ElementFrame& frame) override {
    MappingReader r(ctx_, node, "Resource node");
    r.take({"type"});
    std::string name;
    if (auto n = r.take({"name"})) name = n->scalar;
    yaml::NodeRef uri = r.take({"uri"});
    yaml::NodeRef fragment = r.take({"node", "fragment"});
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
    inner.X_LF = frame.X_LF * X;
    r.take({"crease_angle", "creaseAngle"});
    r.report_unknown({"type", "name", "uri", "node", "fragment", "metadata", "translation", "rotation", "scale",
                      "crease_angle"});
    if (!uri) {
      ctx_.error("load-missing-key", node, "key \"uri\" is not found in a Resource node");
      return;
    }
    std::string path = resolve_uri(ctx_, uri, uri->scalar, uri->location.file);
    if (path.empty()) return;
    std::string ext = lower_extension(path);
    if (ext == ".yaml" || ext == ".yml") {
      read_yaml_fragment(reader, uri, path, fragment, inner);
      return;
    }
    Shape shape;
    shape.name = name;
    shape.source = node.use_site();
    MeshResource mesh;
    mesh.uri = uri->scalar;
    mesh.resolved_path = path;
    if (fragment) mesh.node = fragment->scalar;
    if (metadata) read_mesh_metadata(ctx_, metadata, mesh);
    if (!std::filesystem::exists(path)) {
      ctx_.error("resource-missing", uri, "the resource \"" + uri->scalar + "\" is not found at \"" + path + "\"");
      return;
    }
    shape.geometry = mesh;
    reader.add_shape(std::move(shape), inner);
  }

  void read_link_node(const yaml::NodeRef& node, const std::string& type, std::vector<LinkEntry>&) override {
    ctx_.error("load-unsupported", node, "\"" + type + "\" link nodes are not supported yet");
  }

 private:
  const yaml::Document* load_yaml_file(const yaml::NodeRef& at, const std::string& path) {
    auto it = yaml_files_.find(path);
    if (it != yaml_files_.end()) return it->second.get();
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      ctx_.error("resource-missing", at, "YAML resource \"" + path + "\" cannot be read");
      yaml_files_[path] = nullptr;
      return nullptr;
    }
    std::ostringstream text;
    text << in.rdbuf();
    yaml::ParseOptions po;
    po.max_expanded_nodes = options_.max_expanded_yaml_nodes;
    po.max_depth = options_.max_yaml_depth;
    // body-format-spec §9.3: the resource sees the main body file's anchors.
    if (main_) po.imported_anchors = &main_->anchors;
    auto doc = yaml::parse_yaml(text.str(), path, po, ctx_.sink);
    const yaml::Document* result = doc.get();
    yaml_files_[path] = std::move(doc);
    return result;
  }

  void read_yaml_fragment(ElementReader& reader, const yaml::NodeRef& uri, const std::string& path,
                          const yaml::NodeRef& fragment, const ElementFrame& frame) {
    const yaml::Document* doc = load_yaml_file(uri, path);
    if (!doc) return;
    if (!fragment) {
      reader.read_elements(doc->root, frame);
      return;
    }
    const std::string& name = fragment->scalar;
    const yaml::Node* target = nullptr;
    if (auto it = doc->anchors.find(name); it != doc->anchors.end()) target = it->second;
    else if (main_) {
      if (auto m = main_->anchors.find(name); m != main_->anchors.end()) target = m->second;
    }
    if (!target) {
      ctx_.error("resource-fragment", fragment, "fragment \"" + name + "\" is not found in \"" + uri->scalar + "\"");
      return;
    }
    yaml::NodeRef ref{target, fragment.use_site()};
    reader.read_elements(ref, frame);
  }

  const LoadOptions& options_;
  LoadContext& ctx_;
  Model& model_;
  const yaml::Document* main_;
  std::map<std::string, std::unique_ptr<yaml::Document>> yaml_files_;
};

}  // namespace

std::unique_ptr<ResourceReader> make_resource_handler(const LoadOptions& options, LoadContext& ctx, Model& model,
                                                      const yaml::Document* main_document) {
  return std::make_unique<Resources>(options, ctx, model, main_document);
}

}  // namespace bodyfmt::detail
