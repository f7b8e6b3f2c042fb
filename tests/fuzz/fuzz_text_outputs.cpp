// libFuzzer target: every text output of a loaded model parses (issue 26). bodyinfo's YAML is
// read back by libyaml and its model name must come back exactly; bodycheck's JSON and SARIF
// are read by a strict JSON parser; the GCC-style text holds no control character but line
// breaks and tabs, so that each diagnostic stays one line and moves no terminal.
#include "fuzz_files.h"

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>
#include <bodyfmt/report.h>
#include <bodyfmt/validate.h>

#include "bodyinfo_report.h"
#include "json.h"

#include <yaml.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace {

[[noreturn]] void fail(const char* what, const std::string& text) {
  std::fprintf(stderr, "%s:\n%s\n", what, text.c_str());
  std::abort();
}

/// The YAML document's scalars in order, or nullopt when libyaml refuses the text.
std::optional<std::vector<std::string>> yaml_scalars(const std::string& text) {
  yaml_parser_t parser;
  yaml_parser_initialize(&parser);
  yaml_parser_set_input_string(&parser, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  std::vector<std::string> scalars;
  bool ok = true;
  for (bool done = false; !done;) {
    yaml_event_t event;
    if (!yaml_parser_parse(&parser, &event)) {
      ok = false;
      break;
    }
    if (event.type == YAML_SCALAR_EVENT)
      scalars.emplace_back(reinterpret_cast<const char*>(event.data.scalar.value), event.data.scalar.length);
    done = event.type == YAML_STREAM_END_EVENT;
    yaml_event_delete(&event);
  }
  yaml_parser_delete(&parser);
  if (!ok) return std::nullopt;
  return scalars;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string main = fuzz::write_folder(data, size);
  bodyfmt::LoadOptions options;
  options.max_expanded_yaml_nodes = 200'000;
  options.max_yaml_depth = 64;
  options.max_file_bytes = 1 << 20;
  options.load_meshes = false;
  bodyfmt::CollectingSink sink;
  auto model = bodyfmt::load_body(main, options, sink);
  if (model) {
    const bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
    bodyfmt::validate::check_model(*model, derived, {}, sink);
    const std::vector<bodyfmt::LinkBounds> boxes = bodyfmt::compute_choreonoid_bounds(*model, sink);
    const std::string yaml = bodyfmt::tools::format_reference_yaml(*model, derived, boxes, sink.diagnostics());
    const auto scalars = yaml_scalars(yaml);
    if (!scalars) fail("bodyinfo --format yaml does not parse", yaml);
    // The value after the key model_name; an invalid UTF-8 name comes back with U+FFFD.
    const auto key = std::find(scalars->begin(), scalars->end(), "model_name");
    if (key == scalars->end() || key + 1 == scalars->end() ||
        (key[1] != model->name && key[1].find("\xEF\xBF\xBD") == std::string::npos))
      fail("bodyinfo --format yaml does not give the model name back", yaml);
  }
  bodyfmt::Report report;
  report.files.push_back(main);
  report.diagnostics = sink.diagnostics();
  bodyfmt::ToolInfo tool;
  tool.version = "0";
  tool.information_uri = "https://choreonoid.org/";
  for (const std::string& json :
       {bodyfmt::format_json_report(report, tool), bodyfmt::format_sarif_report(report, tool)}) {
    std::string error;
    if (!bodyfmt::gltf::Json::parse(json, &error)) fail(("JSON does not parse: " + error).c_str(), json);
  }
  bodyfmt::SourceLines sources;
  const std::string text = bodyfmt::format_text_report(report, sources);
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n' && c != '\t') || u == 0x7F) fail("a control character in the text report", text);
  }
  return 0;
}
