// libFuzzer target: the MJCF exporter on every model the loader accepts from the input
// (fuzz_files.h). Besides crashes, leaks and undefined behaviour it checks one promise of
// body2mjcf: an export that succeeds without errors is one MuJoCo 2.2.2 compiles. A model
// MuJoCo refuses must be refused by us first, at its source line, never written.
#include "fuzz_files.h"
#include "mjcf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string main = fuzz::write_folder(data, size);
  bodyfmt::LoadOptions options;
  options.max_expanded_yaml_nodes = 200'000;
  options.max_yaml_depth = 64;
  options.max_file_bytes = 1 << 20;
  bodyfmt::CollectingSink sink;
  auto model = bodyfmt::load_body(main, options, sink);
  if (!model || sink.error_count() > 0) return 0;
  const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
  if (sink.error_count() > 0) return 0;
  bodyfmt::mjcf::MjcfOptions mjcf_options;
  mjcf_options.balance_inertia = true;
  mjcf_options.actuators = bodyfmt::mjcf::Actuators::kPosition;
  const auto xml = fuzz::scratch_folder() / "out" / "robot.xml";
  bodyfmt::converters::OutputSet output(xml);
  if (!bodyfmt::mjcf::write_mjcf(*model, derived, mjcf_options, output, sink) || sink.error_count() > 0) return 0;
  if (!output.commit(sink)) return 0;
  char error[1000] = "";
  mjModel* compiled = mj_loadXML(xml.c_str(), nullptr, error, sizeof error);
  if (!compiled) {
    std::fprintf(stderr, "fuzz_mjcf: body2mjcf wrote an MJCF MuJoCo refuses: %s\n", error);
    std::abort();
  }
  mj_deleteModel(compiled);
  return 0;
}
