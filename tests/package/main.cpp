// Loads a body through an installed bodyfmt and checks SimpleTank's total mass (18 kg), then
// reads a YAML text through the public YAML API and quotes a name for JSON, as another tool's
// own input and output would.
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>
#include <bodyfmt/text.h>
#include <bodyfmt/yaml.h>

#include <cmath>
#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: package_consumer simpletank.body\n";
    return 2;
  }
  bodyfmt::CollectingSink sink;
  std::optional<bodyfmt::Model> model = bodyfmt::load_body(argv[1], {}, sink);
  for (const bodyfmt::Diagnostic& d : sink.diagnostics()) std::cerr << bodyfmt::format_diagnostic(d) << '\n';
  if (!model || sink.error_count() > 0) {
    std::cerr << "FAIL: the body did not load cleanly\n";
    return 1;
  }
  bodyfmt::Derived derived = bodyfmt::compute_derived(*model, sink);
  std::cout << model->name << ": " << model->links.size() << " links, " << derived.total_mass << " kg\n";
  if (model->links.size() != 5 || std::abs(derived.total_mass - 18.0) > 1e-9) {
    std::cerr << "FAIL: expected 5 links and 18 kg\n";
    return 1;
  }
  bodyfmt::CollectingSink yaml_sink;
  std::optional<bodyfmt::YamlDocument> doc =
      bodyfmt::parse_yaml_text("duration: 2.5\nspeed: fast\n", "in.yaml", yaml_sink);
  bodyfmt::YamlReader reader(yaml_sink, "config-invalid");
  const std::optional<double> duration =
      doc ? reader.number(doc->root().find("duration")->value, "'duration'") : std::nullopt;
  const std::optional<double> speed = doc ? reader.number(doc->root().find("speed")->value, "'speed'") : std::nullopt;
  if (duration != 2.5 || speed || yaml_sink.diagnostics().size() != 1 ||
      bodyfmt::format_diagnostic(yaml_sink.diagnostics()[0]) !=
          "in.yaml:2:8: error: 'speed' must be a number [config-invalid]" ||
      bodyfmt::text::json_quote(model->name + "\n") != "\"" + model->name + "\\n\"") {
    std::cerr << "FAIL: the YAML or text API\n";
    for (const bodyfmt::Diagnostic& d : yaml_sink.diagnostics()) std::cerr << bodyfmt::format_diagnostic(d) << '\n';
    return 1;
  }
  std::cout << "OK\n";
  return 0;
}
