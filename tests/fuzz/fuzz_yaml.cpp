// libFuzzer target: the YAML layer (parse_yaml) on arbitrary bytes, with budgets small enough
// that every input is fast; whatever it finds must come back as diagnostics, never a crash.
#include "yaml/yaml_node.h"

#include <bodyfmt/diagnostic.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bodyfmt::yaml::ParseOptions options;
  options.max_expanded_nodes = 200'000;
  options.max_depth = 64;
  bodyfmt::CollectingSink sink;
  auto document = bodyfmt::yaml::parse_yaml(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.yaml",
                                            options, sink);
  if (document && document->root) (void)document->root->is_null();
  return 0;
}
