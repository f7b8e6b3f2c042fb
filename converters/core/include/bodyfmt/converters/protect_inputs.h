#pragma once
/// The files a loaded model was read from, protected from the export that reads them.
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/model.h>

namespace bodyfmt::converters {

/// Protects in `output` the model file, every included .body/YAML file an element came from
/// (SubBody, Resource fragments), every mesh and every texture of `model`.
void protect_inputs(OutputSet& output, const Model& model);

}  // namespace bodyfmt::converters
