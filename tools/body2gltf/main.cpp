// body2gltf: writes a glTF 2.0 model (GLB, or .gltf + .bin + textures) for a Choreonoid .body
// model. Exit codes (tools/common/front.h): 0 written with nothing lost; 1 written, with
// losses or other findings reported; 2 not written (bad usage, the model cannot be loaded, a
// fatal problem, or --strict losses).

#include "export_run.h"
#include "front.h"
#include "gltf_writer.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/derived.h>

#include <unistd.h>

#include <algorithm>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("body2gltf", "Export a Choreonoid .body model to glTF 2.0 (.glb or .gltf)", {false, true});
  std::string output;
  bool collision = false, both = false;
  CLI::App& app = front.app();
  app.add_option("-o,--output", output,
                 "the .glb (binary) or .gltf (JSON + .bin + textures) file to write; '-', a pipe or a device "
                 "gets GLB")
      ->required();
  auto* c = app.add_flag("--collision", collision, "export the collision model instead of the visual one");
  app.add_flag("--both", both, "export visual and collision models under separate nodes (collision hidden)")
      ->excludes(c);
  if (auto code = front.parse(argc, argv)) return *code;
  std::string ext = std::filesystem::path(output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  // A stream (standard output, a FIFO, a device) takes the one self-contained form, GLB.
  std::error_code ec;
  const bool stream =
      output == "-" || (std::filesystem::exists(output, ec) && !std::filesystem::is_regular_file(output, ec) &&
                        !std::filesystem::is_directory(output, ec));
  if (ext != ".glb" && ext != ".gltf" && !stream) {
    front.print_error("-o must name a .glb or .gltf file: " + output);
    return tools::kExitFatal;
  }
  if (output == "-" && ::isatty(STDOUT_FILENO)) {
    front.print_error("-o - would write binary GLB to a terminal; redirect standard output or name a file");
    return tools::kExitFatal;
  }
  gltf::GltfOptions options;
  options.binary = ext == ".glb" || stream;
  options.geometry = both        ? gltf::GeometrySet::kBoth
                     : collision ? gltf::GeometrySet::kCollision
                                 : gltf::GeometrySet::kVisual;
  options.version = BODYFMT_VERSION;

  return tools::run_export(
      front, output, [&](const Model& model, const Derived& derived, converters::OutputSet& out, DiagnosticSink& sink) {
        return gltf::write_gltf(model, derived, options, out, sink);
      });
}
