#pragma once
/// The files a loaded model was read from: what every output of a run must never write over.
#include <bodyfmt/export.h>
#include <bodyfmt/model.h>

#include <string>
#include <vector>

#pragma GCC visibility push(default)
namespace bodyfmt {

struct InputFile {
  std::string path;
  std::string what;  ///< "the model", "a model file it includes", "a mesh of the model", "a texture of the model"
};

/// The model file, every included .body/YAML file an element came from (SubBody, Resource
/// fragments), every mesh and every texture of `model`, each once, in that order; then, once
/// note_standard_input_read() was called and standard input is a regular file, that file (as
/// "/dev/stdin", which stat() follows to it).
std::vector<InputFile> input_files(const Model& model);

/// Tells input_files() that this process reads a model from standard input (the tools' front
/// does): `tool - -o m.body < m.body` must not replace the file it reads (issue 34). Standard
/// input is one per process, so this is too.
void note_standard_input_read();

}  // namespace bodyfmt
#pragma GCC visibility pop
