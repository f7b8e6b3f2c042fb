#include "output_guard.h"

#include <sys/stat.h>

namespace bodyfmt::tools {

std::string input_clash(const std::string& output, const std::vector<InputFile>& inputs) {
  struct stat out {};
  // stat() follows every link, so a link to an input is the input.
  if (output.empty() || output == "-" || ::stat(output.c_str(), &out) != 0) return {};
  if (S_ISDIR(out.st_mode)) return "it is a folder";
  for (const InputFile& input : inputs) {
    struct stat in {};
    if (input.path != "-" && ::stat(input.path.c_str(), &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino)
      return "it is " + input.what + " of this run ('" + input.path + "')";
  }
  return {};
}

}  // namespace bodyfmt::tools
