#pragma once
// Everything a body file pulls in from other files: Resource nodes (meshes and YAML element
// libraries) and the link-level composition nodes SubBody and ContinuousTrack
// (body-format-spec §8.5, §9.3, §11).

#include <bodyfmt/load.h>

#include "load/elements.h"
#include "load/link_reader.h"

#include <memory>
#include <vector>

namespace bodyfmt::detail {

class ResourceReader : public ResourceHandler {
 public:
  /// Reads a SubBody or ContinuousTrack node of `links`, appending links (and one LinkEntry
  /// per link) exactly as read_link does.
  virtual void read_link_node(const yaml::NodeRef& node, const std::string& type, std::vector<LinkEntry>& entries) = 0;
};

struct LoadSession;
std::unique_ptr<ResourceReader> make_resource_handler(const LoadOptions& options, LoadContext& ctx, Model& model,
                                                      const yaml::Document* main_document, LoadSession& session);

}  // namespace bodyfmt::detail
