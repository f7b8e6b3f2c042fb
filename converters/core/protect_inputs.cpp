#include <bodyfmt/converters/protect_inputs.h>
#include <bodyfmt/input_files.h>

namespace bodyfmt::converters {

void protect_inputs(OutputSet& output, const Model& model) {
  for (InputFile& file : input_files(model)) output.protect(file.path, std::move(file.what));
}

}  // namespace bodyfmt::converters
