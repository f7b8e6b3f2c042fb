#pragma once
// Device nodes (body-format-spec §10) and plugin node types Choreonoid loads only with a plugin.

#include <bodyfmt/model.h>

#include "load/mapping_reader.h"

#include <string_view>

namespace bodyfmt::detail {

bool is_core_device_type(std::string_view type);

/// Records the upgrade edit of an angle Choreonoid converts but the model does not keep: the
/// first of `names` present (an axis-angle rotation when `rotation`).
void note_first_angle(MappingReader& r, KeyNames names, bool rotation);
bool is_plugin_node_type(std::string_view type);

/// Reads the parameters of a device node whose common keys (name, id, on, transform,
/// elements) the element reader has already taken. Returns false when Choreonoid would drop
/// the device (a Camera without a valid format).
bool read_device_params(MappingReader& r, std::string_view node_type, Device& device);

}  // namespace bodyfmt::detail
