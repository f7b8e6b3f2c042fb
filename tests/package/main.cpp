// Loads a body through an installed bodyfmt and checks SimpleTank's total mass (18 kg).
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

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
  std::cout << "OK\n";
  return 0;
}
