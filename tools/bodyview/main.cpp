// bodyview: writes one self-contained HTML page that shows a Choreonoid .body model in a
// browser (three.js, inline), with joint sliders, collision and mass display and bodycheck's
// findings; --serve serves it on a loopback port and rebuilds it when the model changes.
// Exit codes (tools/common/front.h): 0 written, nothing at or above the fail level; 1 written,
// with findings; 2 not written (bad usage, the model cannot be loaded, an unwritable output).

#include "front.h"
#include "page.h"
#include "render.h"
#include "report.h"
#include "serve.h"

#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/converters/protect_inputs.h>

#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("bodyview", "Show a Choreonoid .body model in a browser: one self-contained HTML file", {});
  std::string output;
  bool serve = false;
  bool verbose = false;
  int port = 0;
  int lifeline = -1;
  CLI::App& app = front.app();
  auto* o = app.add_option("-o,--output", output,
                           "the .html file to write ('-': standard output; default: MODEL.html in the current folder)");
  auto* s = app.add_flag("--serve", serve,
                         "serve the page on 127.0.0.1 and rebuild it when the model, a file it includes or a mesh "
                         "changes (until interrupted)");
  app.add_option("--port", port, "the port for --serve (default: any free one)")->check(CLI::Range(0, 65535))->needs(s);
  app.add_option("--lifeline", lifeline,
                 "with --serve: exit at once when file descriptor FD (the read end of a pipe) reaches its end, "
                 "that is when every writer has closed it; the program that starts bodyview holds the write end, "
                 "so bodyview ends with it however it ends (bodyls does this)")
      ->check(CLI::Range(0, 1 << 20))
      ->needs(s)
      ->type_name("FD");
  s->excludes(o);
  app.add_flag("--verbose", verbose,
               "print every finding (default: one summary line, as the page lists them; findings are printed "
               "in full when no page is written)");
  if (auto code = front.parse(argc, argv)) return *code;
  // First of all: a model that takes long to load (or never does) must not outlive its starter.
  if (lifeline >= 0 && !bodyview::exit_with_lifeline(lifeline)) {
    front.print_error("--lifeline " + std::to_string(lifeline) + ": not a file descriptor open for reading");
    return tools::kExitFatal;
  }
  // Without -o the page goes to the current folder, named after the model, as a download
  // would: the model's own folder may be read-only or shared (a package, a corpus), and a
  // generated page beside it would be mixed into the sources. Over the model itself (a model
  // named NAME.html) it is refused, as every output over an input is.
  if (!serve && output.empty()) {
    if (front.inputs().front() == "-") {
      front.print_error("name the page with -o FILE.html when the model comes from standard input, or use --serve");
      return tools::kExitFatal;
    }
    output = std::filesystem::path(front.inputs().front()).stem().string() + ".html";
  }
  const std::filesystem::path assets = bodyview::find_assets(argc > 0 ? argv[0] : nullptr);
  if (assets.empty()) {
    front.print_error("the viewer files (viewer.js, three.js) are not installed beside bodyview");
    return tools::kExitFatal;
  }
  const std::string& path = front.inputs().front();
  auto policy = front.policy_for(path);
  if (!policy) return tools::kExitFatal;
  if (serve) return bodyview::serve(front, *policy, path, assets, port, verbose);

  bodyview::Rendered r = bodyview::render(front, *policy, path, assets, "");
  bool written = false;
  CollectingSink commit;
  if (r.page && r.model) {
    converters::OutputSet out(output);
    converters::protect_inputs(out, *r.model);
    out.set_main(std::move(*r.page));
    written = out.commit(commit);
  }
  // Without a page nobody sees the findings but here: they are printed in full.
  if (written)
    bodyview::report_page_findings(front, r.diagnostics, verbose,
                                   output == "-" ? "written to standard output" : output);
  else
    front.print(r.diagnostics);
  front.print(commit.diagnostics());
  for (const Diagnostic& d : commit.diagnostics()) r.diagnostics.push_back(d);
  if (!written) front.print_error(output + " was not written");
  if (written && output != "-") std::cerr << "bodyview: wrote " << output << " (open it in a browser)\n";
  return tools::exit_code(r.diagnostics, policy->exit, !written);
}
