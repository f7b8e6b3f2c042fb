#pragma once
/// The values a writer writes other than the model gives them, said in the same words by every
/// writer (export-value-changed, at the value): here the joint axis, which every target reads as
/// a direction while Choreonoid uses it as given. Whether an axis is changed is the
/// physical-validity gate's word (bodyfmt/physical.h, joint-axis-not-unit), so bodycheck's
/// warning and each writer's report are one finding at one place.
#include <bodyfmt/diagnostic.h>
#include <bodyfmt/model.h>
#include <bodyfmt/physical.h>

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace bodyfmt::converters {

struct ValueChange {
  SourceLocation at;  ///< the gate's place for the value
  std::string what;   ///< the value read, the value written and why
};

/// The axis of link `index` as a writer writes it: its direction (the axis as given when it has
/// none; check_joints refuses such a joint first).
Eigen::Vector3d axis_direction(const Link& link);

/// The change a writer makes when it writes the axis of link `index` as its direction, for an
/// axis the gate finds not of unit length among `joint_findings` (assess_joints()); nullopt for
/// an axis written unchanged (within kUnitAxisTolerance it is normalised without a word, as
/// bodycheck is silent on it). `reader` names who reads the axis as a direction ("URDF").
std::optional<ValueChange> axis_change(const Model& model, const std::vector<PhysicalFinding>& joint_findings,
                                       std::size_t index, std::string_view reader);

}  // namespace bodyfmt::converters
