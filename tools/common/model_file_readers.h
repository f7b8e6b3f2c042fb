#pragma once
/// The model formats every tool reads through a wrapper body file's `model_file`
/// (body-format-spec §2.4) besides the .body formats libbodyfmt reads itself: .urdf, through
/// the URDF reader (converters/urdf), located in the URDF.

#include <bodyfmt/load.h>

namespace bodyfmt::tools {

/// Installs the readers in `options.model_file_readers`.
void add_model_file_readers(LoadOptions& options);

}  // namespace bodyfmt::tools
