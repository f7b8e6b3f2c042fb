#pragma once
// Reads a whole body file: header, links, tree, extra joints (body-format-spec §2, §5, §12).

#include <bodyfmt/load.h>
#include <bodyfmt/mesh_import.h>

#include "load/elements.h"
#include "load/load_context.h"
#include "load/name_index.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace bodyfmt::detail {

/// State shared by the main file and every file it includes, for one load.
struct LoadSession {
  MeshCache meshes;
  /// Sub-body models by canonical path; nullptr when the file could not be loaded.
  std::map<std::string, std::shared_ptr<const Model>> subbodies;
  /// Canonical paths of the body files being read, outermost first (recursion detection).
  std::vector<std::string> chain;
  /// While a wrapper body file's model is read (§2.4): the division number of primitives that
  /// give none, and the model's name unless the file sets one.
  int default_division_number = 20;
  std::string default_model_name;
};

/// The top-level keys other Choreonoid subsystems read from the body info (§2.3).
const std::vector<std::string_view>& known_body_info_keys();

class BodyReader {
 public:
  BodyReader(const LoadOptions& options, DiagnosticSink& sink, LoadSession& session);
  ~BodyReader();
  /// `top_level`: the file the user asked for (imports meshes once everything is read).
  std::optional<Model> read(std::string_view text, const std::string& file_name, bool top_level = true);

 private:
  class LinkStream;
  /// Sends every diagnostic to whichever sink is current: while links are read during the
  /// parse, their findings wait until the header's are out, or are dropped when the file has
  /// to be read again.
  class RedirectSink : public DiagnosticSink {
   public:
    explicit RedirectSink(DiagnosticSink& target) : target_(&target) {}
    void report(Diagnostic diagnostic) override { target_->report(std::move(diagnostic)); }
    void redirect(DiagnosticSink& target) { target_ = &target; }

   private:
    DiagnosticSink* target_;
  };

  /// One reading of the file; sets `read_again` when links read during the parse turn out to
  /// have been read with the wrong header (written after `links`, see LinkStream).
  std::optional<Model> read_once(std::string_view text, const std::string& file_name, bool top_level, bool stream,
                                 bool& read_again);
  bool read_header(LoadContext& ctx, const yaml::NodeRef& root, Model& model);
  void read_links(const yaml::NodeRef& links, Model& model, std::vector<struct LinkEntry>& entries);
  /// One item of a `links` sequence.
  void read_link_item(const yaml::NodeRef& item, Model& model, std::vector<struct LinkEntry>& entries);
  /// A Link, SubBody, ContinuousTrack or Skip node of `links`.
  void read_link_node(const yaml::NodeRef& node, const std::string& type, Model& model,
                      std::vector<struct LinkEntry>& entries);
  /// Orders the links depth-first from the root and sets parents and children (§5.2).
  bool build_tree(Model& model, const std::vector<struct LinkEntry>& entries, const yaml::NodeRef& root_link);
  /// Views of the names in `Model::links`: valid while the links are neither added nor moved.
  struct LinkNames {
    NameIndex by_name;
    NameIndex by_joint_name;
  };
  /// With the ContinuousTrack names of `entries` (LinkEntry::alias).
  LinkNames index_link_names(const Model& model, const std::vector<struct LinkEntry>& entries);
  /// load-track-name at `where`, a place that names `link` by its ContinuousTrack node's name.
  void track_name_used(const Model& model, LinkIndex link, const SourceLocation& where);
  std::vector<LinkIndex> link_parents(const Model& model, const std::vector<struct LinkEntry>& entries,
                                      const LinkNames& names, LinkIndex root);
  void reorder_links(Model& model, const std::vector<LinkIndex>& order, const std::vector<LinkIndex>& parent,
                     std::vector<std::vector<LinkIndex>>& children);
  void read_extra_joints(const yaml::NodeRef& extra_joints, Model& model);
  void import_meshes(Model& model);
  /// load-format-upgrade for a format < 2.0 file, carrying the upgrade fix-its (§2.1, §3).
  void report_upgrade(const Model& model);

  const LoadOptions& options_;
  DiagnosticSink& sink_;
  RedirectSink redirect_;
  LoadContext ctx_;  ///< reports to redirect_
  LoadSession& session_;
  std::unique_ptr<class ResourceReader> resources_;
  std::vector<std::unique_ptr<yaml::Document>> documents_;
  yaml::NodeRef version_node_;  ///< format_version's value
  yaml::NodeRef unit_node_;     ///< angle_unit's value, when given
};

}  // namespace bodyfmt::detail
