#pragma once
// Reads a whole body file: header, links, tree, extra joints (body-format-spec §2, §5, §12).

#include <bodyfmt/load.h>

#include "load/elements.h"
#include "load/load_context.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::detail {

class BodyReader {
 public:
  BodyReader(const LoadOptions& options, DiagnosticSink& sink);
  ~BodyReader();
  std::optional<Model> read(const std::string& text, const std::string& file_name);

 private:
  bool read_header(const yaml::NodeRef& root, Model& model);
  void read_links(const yaml::NodeRef& links, Model& model, std::vector<struct LinkEntry>& entries);
  bool build_tree(Model& model, const std::vector<struct LinkEntry>& entries, const yaml::NodeRef& root_link);
  void read_extra_joints(const yaml::NodeRef& extra_joints, Model& model);

  const LoadOptions& options_;
  LoadContext ctx_;
  std::unique_ptr<class ResourceReader> resources_;
  std::vector<std::unique_ptr<yaml::Document>> documents_;
};

}  // namespace bodyfmt::detail
