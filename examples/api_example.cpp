// Load a .body file, print its diagnostics, then each link's mass and world position.
#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: api_example FILE.body\n";
    return 2;
  }
  bodyfmt::CollectingSink sink;
  std::optional<bodyfmt::Model> model = bodyfmt::load_body(argv[1], {}, sink);
  bodyfmt::Derived derived;
  if (model) derived = bodyfmt::compute_derived(*model, sink);
  for (const bodyfmt::Diagnostic& d : sink.diagnostics()) std::cerr << bodyfmt::format_diagnostic(d) << '\n';
  if (!model) return 2;
  for (std::size_t i = 0; i < model->links.size(); ++i) {
    Eigen::Vector3d p = derived.X_WL[i].translation();
    std::cout << model->links[i].name << ": " << derived.mass[i].mass << " kg at (" << p.x() << ", " << p.y() << ", "
              << p.z() << ")\n";
  }
  return sink.error_count() > 0 ? 1 : 0;
}
