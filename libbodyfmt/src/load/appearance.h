#pragma once
// Shape appearance: material and texture (body-format-spec §8.7).

#include <bodyfmt/model.h>

#include "load/load_context.h"

namespace bodyfmt::detail {

Appearance read_appearance(LoadContext& ctx, const yaml::NodeRef& appearance);

}  // namespace bodyfmt::detail
