// libFuzzer target: the whole loader (YAML, keys, SubBody and YAML resources, mesh files
// through the VRML reader and assimp) and the derived data, on a folder of files (fuzz_files.h).
#include "fuzz_files.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string main = fuzz::write_folder(data, size);
  bodyfmt::LoadOptions options;
  options.max_expanded_yaml_nodes = 200'000;
  options.max_yaml_depth = 64;
  options.max_file_bytes = 1 << 20;
  bodyfmt::CollectingSink sink;
  if (auto model = bodyfmt::load_body(main, options, sink)) {
    const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
    (void)bodyfmt::compute_choreonoid_bounds(*model, sink);
    (void)derived;
  }
  return 0;
}
