// libFuzzer target: the whole loader (YAML, keys, SubBody and YAML resources, wrapper body files
// around a .body or a URDF, mesh files through the VRML reader and assimp) and the derived data,
// on a folder of files (fuzz_files.h).
// Differential too: links read during the parse (the default) must give the findings and the
// link tree of a load from the whole YAML tree (LoadOptions::stream_links = false).
#include "fuzz_files.h"
#include "model_file_readers.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <cstdio>
#include <cstdlib>

namespace {

std::string summary(const std::optional<bodyfmt::Model>& model, const bodyfmt::CollectingSink& sink) {
  std::string out;
  for (const bodyfmt::Diagnostic& d : sink.diagnostics()) {
    out += d.rule_id + " " + d.location.file.str() + ":" + std::to_string(d.location.line) + ":" +
           std::to_string(d.location.column) + " " + d.message + "\n";
  }
  if (model)
    for (const bodyfmt::Link& link : model->links) out += link.name + " <- " + std::to_string(link.parent) + "\n";
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string main = fuzz::write_folder(data, size);
  bodyfmt::LoadOptions options;
  options.max_expanded_yaml_nodes = 200'000;
  options.max_yaml_depth = 64;
  options.max_file_bytes = 1 << 20;
  bodyfmt::tools::add_model_file_readers(options);
  bodyfmt::CollectingSink sink;
  auto model = bodyfmt::load_body(main, options, sink);
  if (model) {
    const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
    (void)bodyfmt::compute_choreonoid_bounds(*model, sink);
    (void)derived;
  }
  bodyfmt::CollectingSink streamed_sink, whole_sink;
  options.load_meshes = false;  // the same either way, and fuzzed above
  const auto streamed = bodyfmt::load_body(main, options, streamed_sink);
  options.stream_links = false;
  const auto whole = bodyfmt::load_body(main, options, whole_sink);
  const std::string a = summary(streamed, streamed_sink), b = summary(whole, whole_sink);
  if (a != b) {
    std::fprintf(stderr, "streamed links differ from the whole tree:\n--- streamed\n%s--- whole\n%s", a.c_str(),
                 b.c_str());
    std::abort();
  }
  return 0;
}
