#pragma once
// Everything a body file pulls in from other files: Resource nodes (meshes and YAML element
// libraries) and the link-level composition nodes SubBody and ContinuousTrack
// (body-format-spec §8.5, §9.3, §11).

#include <bodyfmt/load.h>

#include "load/elements.h"
#include "load/link_reader.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::detail {

class ResourceReader : public ResourceHandler {
 public:
  /// Reads a SubBody or ContinuousTrack node of `links`, appending links (and one LinkEntry
  /// per link) exactly as read_link does.
  virtual void read_link_node(const yaml::NodeRef& node, const std::string& type, std::vector<LinkEntry>& entries) = 0;
  /// The main body file's document, whose anchors YAML resources see (body-format-spec §9.3).
  /// While the links are read during the parse, there is none yet.
  virtual void set_main_document(const yaml::Document* main_document) = 0;
  /// Whether a YAML resource was read while there was no main document: it may have missed an
  /// anchor of the main file, so the file must be read again with its whole tree.
  virtual bool read_yaml_without_main_document() const = 0;
};

/// An included file's text (SubBody, YAML resource, a wrapper's model file): the stand-in of
/// LoadOptions::file_texts, else the regular file on disk within the size limit.
std::optional<std::string> read_included_file(const std::string& path, const LoadOptions& options, std::string& why);

/// Tells LoadOptions::on_model_text that `path` was read as model text, so a report may quote
/// it. Called once the text turned out to be a model, never for a file merely named.
void note_model_text(const LoadOptions& options, const std::string& path);

struct LoadSession;
std::unique_ptr<ResourceReader> make_resource_handler(const LoadOptions& options, LoadContext& ctx, Model& model,
                                                      LoadSession& session);

}  // namespace bodyfmt::detail
