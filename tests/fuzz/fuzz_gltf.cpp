// libFuzzer target: the glTF exporter on every model the loader accepts from the input
// (fuzz_files.h), as GLB and as .gltf with its .bin, visual and collision geometry both.
// Besides crashes, leaks and undefined behaviour it checks that every GLB written without
// errors is one assimp's own glTF importer reads back.
#include "fuzz_files.h"
#include "gltf_writer.h"

#include <assimp/scene.h>
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>
#include <assimp/Importer.hpp>

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
  if (!model) return 0;
  const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
  for (const bool binary : {true, false}) {
    bodyfmt::gltf::GltfOptions gltf_options;
    gltf_options.binary = binary;
    gltf_options.geometry = bodyfmt::gltf::GeometrySet::kBoth;
    const auto path = fuzz::scratch_folder() / "out" / (binary ? "robot.glb" : "robot.gltf");
    bodyfmt::converters::OutputSet output(path);
    const int errors_before = sink.error_count();
    if (!bodyfmt::gltf::write_gltf(*model, derived, gltf_options, output, sink) || !binary) continue;
    if (sink.error_count() > errors_before) continue;
    const std::string& glb = output.files().at(path.filename().string());
    Assimp::Importer importer;
    if (!importer.ReadFileFromMemory(glb.data(), glb.size(), 0, "glb")) {
      std::fprintf(stderr, "fuzz_gltf: assimp cannot read back our GLB: %s\n", importer.GetErrorString());
      std::abort();
    }
  }
  return 0;
}
