#pragma once
// How a field's value is shown (bodydiff's changes, its canonical text, bodycheck --fix's
// difference): numbers in the model's units, rotations as roll-pitch-yaw in degrees.

#include "fields/model_fields.h"

#include <string>

namespace bodyfmt::detail {

/// The value as shown: numbers shortest (`precision` 0) or rounded to `precision` digits.
std::string field_value(const Field& field, int precision = 0);

}  // namespace bodyfmt::detail
