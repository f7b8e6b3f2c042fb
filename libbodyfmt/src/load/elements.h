#pragma once
// The `elements` tree of a link (body-format-spec §7, §8): shapes, rigid bodies, devices,
// transforms, Visual/Collision parts, resources.

#include <bodyfmt/model.h>

#include "load/load_context.h"

#include <set>
#include <string>
#include <vector>

namespace bodyfmt::detail {

enum class ModelPart { kBoth, kVisual, kCollision };

/// A node's own transform from its `translation`, `rotation` and `scale` values (each may be
/// absent): scale first, then rotation, then translation (body-format-spec §4.4); a scene file
/// Transform's `scale_orientation` turns the axes the scale acts along. The one reading of this
/// rule, for the element reader and for a scene file's node lookup alike; problems are reported.
Eigen::Affine3d read_node_transform(LoadContext& ctx, const yaml::NodeRef& translation, const yaml::NodeRef& rotation,
                                    const yaml::NodeRef& scale, const yaml::NodeRef& scale_orientation);

struct ElementFrame {
  Eigen::Affine3d X_LF = Eigen::Affine3d::Identity();  ///< accumulated transform, may scale
  int frame = -1;                                      ///< Link::frames index of the innermost transform node
  ModelPart part = ModelPart::kBoth;
  SourceLocation part_source;  ///< the Visual/Collision node that set `part`
  /// Inside a Choreonoid scene file (.scen, load/scene_file.h): only the scene reader's node
  /// types are defined there (no RigidBody, Visual, Collision or devices).
  bool scene_file = false;
  /// The `scene` value itself, which alone may be one mapping with a `type`; an `elements`
  /// mapping in a scene file is always type-keyed.
  bool scene_top = false;
  /// The metadata length scale of the enclosing scene file: Choreonoid scales its lengths,
  /// not the meshes it includes.
  double scene_length_scale = 1.0;
};

/// Hook for Resource element nodes (meshes and YAML fragments), provided by the resource
/// loader. Returns false when the resource could not be used (already reported).
class ElementReader;
struct ResourceHandler {
  virtual ~ResourceHandler() = default;
  virtual void read_resource(ElementReader& reader, const yaml::NodeRef& node, const ElementFrame& frame) = 0;
  /// A Shape whose geometry is a Resource the handler reads itself (a scene file): adds what
  /// it gives, or reports why not, and returns true; false leaves the shape to the caller.
  virtual bool read_scene_geometry(ElementReader& reader, Shape& shape, const ElementFrame& frame) = 0;
};

class ElementReader {
 public:
  ElementReader(LoadContext& ctx, Model& model, LinkIndex link, ResourceHandler* resources);

  /// Reads an `elements` value in any of its three forms.
  void read_elements(const yaml::NodeRef& elements, const ElementFrame& frame);
  /// Reads one node whose type is known.
  void read_node(const yaml::NodeRef& node, const std::string& type, const ElementFrame& frame);
  /// Reads a mapping as a Shape node (the `shape:` shortcut and type-keyed forms).
  void read_shape(const yaml::NodeRef& node, const ElementFrame& frame);
  void add_shape(Shape shape, const ElementFrame& frame);
  /// Enters a transform node: records it in Link::frames and returns the inner frame.
  ElementFrame push_frame(const ElementFrame& frame, const Eigen::Affine3d& X_PF);

  LoadContext& context() { return ctx_; }
  Model& model() { return model_; }
  LinkIndex link_index() const { return link_; }
  bool has_rigid_body() const { return rigid_bodies_ > 0; }

 private:
  Link& link() { return model_.links[static_cast<std::size_t>(link_)]; }
  /// Enters a node's own translation, rotation and scale (`scale_orientation`: a scene file
  /// Transform's, which orients the scale axes).
  std::optional<ElementFrame> enter(class MappingReader& r, const ElementFrame& frame, bool allow_scale = true,
                                    const yaml::NodeRef& scale_orientation = {});
  /// An element node type the file's grammar does not define (load-unknown-node-type).
  void report_undefined_type(const yaml::NodeRef& node, const std::string& type, const ElementFrame& frame);
  void read_rigid_body(const yaml::NodeRef& node, const ElementFrame& frame);
  void read_device(const yaml::NodeRef& node, const std::string& type, const ElementFrame& frame);
  void read_part(const yaml::NodeRef& node, ModelPart part, const ElementFrame& frame);

  LoadContext& ctx_;
  Model& model_;
  LinkIndex link_;
  ResourceHandler* resources_;
  int rigid_bodies_ = 0;
};

}  // namespace bodyfmt::detail
