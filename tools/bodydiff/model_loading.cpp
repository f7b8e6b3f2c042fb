#include "model_loading.h"

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/load.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>

#include <utility>
#include <vector>

namespace bodyfmt::tools {
namespace {

// Prints the errors that kept a model from loading.
void print_fatal(Front& front, CollectingSink& sink) {
  std::vector<Diagnostic> fatal;
  for (Diagnostic& d : sink.diagnostics())
    if (d.severity >= Severity::kError) fatal.push_back(std::move(d));
  front.print(std::move(fatal));
}

}  // namespace

std::optional<Model> load_quietly(Front& front, const std::string& path, const std::string& name) {
  CollectingSink sink;
  std::optional<Model> model;
  if (name.empty()) {
    if (auto input = front.open_input(path, sink)) model = front.load(*input, sink);
  } else {
    // A git temporary file: loaded under the name of the file in the work tree, so that relative
    // URIs resolve there and locations name it.
    // Bounded like every file read: git hands any path it is given (/dev/zero, a FIFO).
    std::string why;
    if (std::optional<std::string> text = read_regular_file(path, front.load_options().max_file_bytes, why))
      model = load_body_string(*text, name, front.load_options(), sink);
    else
      report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "cannot read \"" + path + "\": " + why);
  }
  if (!model) print_fatal(front, sink);
  return model;
}

std::optional<Model> load_text_quietly(Front& front, const std::string& text, const std::string& name) {
  CollectingSink sink;
  std::optional<Model> model = load_body_string(text, name, front.load_options(), sink);
  if (!model) print_fatal(front, sink);
  return model;
}

}  // namespace bodyfmt::tools
