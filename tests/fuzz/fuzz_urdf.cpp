// libFuzzer target: the URDF exporter on every model the loader accepts from the input
// (fuzz_files.h), with STL and DAE meshes; the output set is staged and never committed.
#include "fuzz_files.h"
#include "urdf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string main = fuzz::write_folder(data, size);
  bodyfmt::LoadOptions options;
  options.max_expanded_yaml_nodes = 200'000;
  options.max_yaml_depth = 64;
  options.max_file_bytes = 1 << 20;
  bodyfmt::CollectingSink sink;
  auto model = bodyfmt::load_body(main, options, sink);
  if (!model) return 0;
  const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
  for (auto format : {bodyfmt::converters::MeshFormat::kStl, bodyfmt::converters::MeshFormat::kDae}) {
    bodyfmt::urdf::UrdfOptions urdf_options;
    urdf_options.mesh_format = format;
    urdf_options.devices_as_frames = format == bodyfmt::converters::MeshFormat::kDae;
    bodyfmt::converters::OutputSet output(fuzz::scratch_folder() / "out" / "robot.urdf");
    bodyfmt::urdf::write_urdf(*model, derived, urdf_options, output, sink);
  }
  return 0;
}
