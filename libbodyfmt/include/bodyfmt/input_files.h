#pragma once
/// The files a loaded model was read from: what every output of a run must never write over.
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <string>
#include <vector>

namespace BODYFMT_API bodyfmt {

struct InputFile {
  std::string path;
  std::string what;  ///< "the model", "a model file it includes", "a mesh of the model", "a texture of the model"
};

/// The model file, every included .body/YAML file an element came from (SubBody, Resource
/// fragments), every mesh and every texture of `model`, each once, in that order.
std::vector<InputFile> input_files(const Model& model);

}  // namespace bodyfmt
