#pragma once
/// What changed between two loaded models (`bodydiff`): links matched by name, their joints,
/// mass data, shapes and devices, and the derived effects a reviewer cares about (total mass
/// and centre of mass, every link's world frame at the zero pose). Also the canonical text form
/// of one model that `bodydiff --textconv` prints for git.
///
/// The comparison reads models, never text: two files that load to the same model (reformatted,
/// keys reordered or respelled, anchors expanded, format 1.0 upgraded to 2.0) have no change.

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <string>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

enum class ChangeKind { kAdded, kRemoved, kChanged };

/// One change. Values are printed as the model holds them: SI units and radians, vectors as
/// `[x, y, z]`, rotations as roll-pitch-yaw in degrees (`rpy`), unlimited as `unlimited`.
struct ModelChange {
  ChangeKind kind = ChangeKind::kChanged;
  std::string link;           ///< the link the change belongs to; empty for the whole model
  std::string field;          ///< e.g. "mass", "joint_range", "shape 2 geometry", "device 'gyro'"
  std::string old_value;      ///< empty when added
  std::string new_value;      ///< empty when removed
  SourceLocation old_source;  ///< where the old value is written (unknown when added)
  SourceLocation new_source;  ///< where the new value is written (unknown when removed)
  bool derived = false;       ///< computed from other fields (total mass, world frames)
};

struct ModelDiffOptions {
  /// Numbers are equal when |a - b| <= tolerance * max(1, |a|, |b|): relative above 1,
  /// absolute below. Ids and counts (a joint_id, a device's id, a camera's width, a shape's
  /// division_number) name something rather than measure it: they compare exactly.
  double tolerance = 1e-9;
  /// Report derived effects (total mass and centre of mass, world frames at the zero pose).
  bool derived = true;
};

/// The changes from `old_model` to `new_model`, grouped by link: the whole model first, then
/// each link of the new model in its order (an added link, its field changes, its world frame),
/// then the removed links in the old model's order. Mesh files are compared by content, so a
/// renamed file with the same bytes is no change. Empty when the models are the same.
std::vector<ModelChange> diff_models(const Model& old_model, const Model& new_model,
                                     const ModelDiffOptions& options = {});

/// A canonical text form of the model for line-based diffs (`git diff` through textconv): the
/// fields diff_models compares, one per line, the whole model first and then the links sorted
/// by name, numbers rounded to 12 significant digits (so the rounding noise of a unit
/// conversion does not show) and no source locations.
std::string canonical_text(const Model& model);

}  // namespace bodyfmt
#pragma GCC visibility pop
