#include "load/body_reader.h"

#include <bodyfmt/body_keys.h>

#include "load/link_reader.h"
#include "load/mapping_reader.h"
#include "load/resource_reader.h"
#include "load/scalar.h"
#include "load/uri.h"
#include "load/values.h"
#include "load/wrapper_reader.h"
#include "text/text_util.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <utility>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace bodyfmt::detail {
namespace {

// body-format-spec §2.3: keys other Choreonoid subsystems read from the body info.
const std::vector<std::string_view> kKnownInfoKeys = {"standard_pose",
                                                      "standardPose",
                                                      "link_group",
                                                      "linkGroup",
                                                      "foot_links",
                                                      "footLinks",
                                                      "symmetric_joints",
                                                      "symmetricJoints",
                                                      "symmetric_ik_links",
                                                      "symmetricIkLinks",
                                                      "default_ik_setup",
                                                      "defaultIKsetup",
                                                      "pose_conversion_info",
                                                      "collision_detection_rules",
                                                      "collisionDetection",
                                                      "available_ik_interpolation_links",
                                                      "default_ik_interpolation_links",
                                                      "body_markers",
                                                      "preset_poses",
                                                      "MultiCopterTargetBody",
                                                      "lipSyncShapes",
                                                      "linearInterpolationJoints",
                                                      "apply_camera_effect"};

/// Asks for transparent huge pages in the 2 MiB-aligned part of `bytes` at `data`, an array
/// that is about to be written front to back once: a page fault per 2 MiB instead of one per
/// 4 KiB (the link array of a 100,000-link file is 60 MB). Only a hint, and none outside Linux.
void advise_huge_pages([[maybe_unused]] const void* data, [[maybe_unused]] std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t{1} << 21;
  const auto at = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (at + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t end = (at + bytes) & ~(kHugePage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

}  // namespace

const std::vector<std::string_view>& known_body_info_keys() { return kKnownInfoKeys; }

BodyReader::BodyReader(const LoadOptions& options, DiagnosticSink& sink, LoadSession& session)
    : options_(options), sink_(sink), redirect_(sink), ctx_(redirect_), session_(session) {
  ctx_.package_paths = options.package_paths;
  ctx_.use_ros_package_path = options.use_ros_package_path;
  ctx_.default_division_number = session.default_division_number;
}

BodyReader::~BodyReader() = default;

/// Reads each item of the top-level `links` sequence as soon as the parser has finished it,
/// so that the YAML tree never holds every link (body files of 100,000 links). Choreonoid
/// reads the header first, wherever it is written; the items are read with the header keys
/// written before `links`, and BodyReader::read_once compares that header with the whole one
/// at the end: when they differ, the file is read again with its whole tree. So is a file
/// whose link read a YAML resource (it may use an anchor written after the link). Items
/// after a SubBody stay in the tree and are read after the parse, in order: a sub-body's
/// findings are reported once per load, which a second reading could not repeat.
class BodyReader::LinkStream : public yaml::SequenceConsumer {
 public:
  LinkStream(BodyReader& reader, std::string_view text, Model& model, std::vector<LinkEntry>& entries)
      : reader_(reader), text_(text), model_(model), entries_(entries) {}

  std::string_view key() const override { return "links"; }

  bool begin(const yaml::Node& head, const yaml::Node& sequence) override {
    if (sequence_ != nullptr) {  // `links` written twice: the last one is read
      conflict_ = true;
      return false;
    }
    CollectingSink silent;  // the header's findings are reported when the whole header is read
    LoadContext probe(silent);
    Model header;
    if (!reader_.read_header(probe, yaml::NodeRef{&head, nullptr, nullptr}, header)) return false;
    degrees_ = probe.degrees;
    format_version_ = header.format_version;
    reader_.ctx_.degrees = degrees_;
    model_.format_version = format_version_;
    model_.angles_in_degrees = degrees_;
    sequence_ = &sequence;
    reserve_links(sequence.location.line);
    return true;
  }

  bool take(const yaml::NodeRef& item) override {
    if (stopped_) return false;
    const yaml::MapEntry* type = item->is_mapping() ? item->find("type") : nullptr;
    const std::string type_name = type ? std::string(type->value->scalar()) : std::string();
    if (type_name == "SubBody") {
      stopped_ = true;
      return false;
    }
    ++taken_;
    reader_.read_link_node(item, type_name, model_, entries_);
    return true;
  }

  /// Whether the items read so far are what the whole file says: `links` is the sequence that
  /// was read, and `model` has the header the items were read with.
  bool matches(const yaml::NodeRef& links, const Model& model, const LoadContext& ctx) const {
    if (conflict_) return false;
    if (sequence_ == nullptr) return taken_ == 0;
    return links.node == sequence_ && model.format_version == format_version_ && ctx.degrees == degrees_;
  }
  std::size_t taken() const { return taken_; }

 private:
  // The number of links is known only at the end. One link per line is the densest layout,
  // so the lines from `links` on bound it: reserving that many keeps the link array from
  // being copied (and its pages touched twice) as it grows. Pages never used cost no memory;
  // past kLargestReservation the array grows as usual.
  void reserve_links(int first_line) {
    constexpr std::size_t kLargestReservation = std::size_t{1} << 20;
    // memchr rather than std::count: about ten times faster on a 24 MB text.
    std::size_t lines = 1;
    const char* const end = text_.data() + text_.size();
    for (const char* at = text_.data(); at < end; ++at, ++lines) {
      at = static_cast<const char*>(std::memchr(at, '\n', static_cast<std::size_t>(end - at)));
      if (at == nullptr) break;
    }
    const std::size_t bound = lines - std::min(lines, static_cast<std::size_t>(first_line));
    model_.links.reserve(std::min(bound, kLargestReservation));
    entries_.reserve(std::min(bound, kLargestReservation));
    advise_huge_pages(model_.links.data(), model_.links.capacity() * sizeof(Link));
  }

  BodyReader& reader_;
  std::string_view text_;
  Model& model_;
  std::vector<LinkEntry>& entries_;
  const yaml::Node* sequence_ = nullptr;
  bool conflict_ = false;
  bool stopped_ = false;
  std::size_t taken_ = 0;
  bool degrees_ = true;
  double format_version_ = 0;
};

std::optional<Model> BodyReader::read(std::string_view text, const std::string& file_name, bool top_level) {
  bool read_again = false;
  std::optional<Model> model = read_once(text, file_name, top_level, options_.stream_links, read_again);
  if (!read_again) return model;
  BodyReader again(options_, sink_, session_);
  return again.read_once(text, file_name, top_level, false, read_again);
}

std::optional<Model> BodyReader::read_once(std::string_view text, const std::string& file_name, bool top_level,
                                           bool stream, bool& read_again) {
  struct ChainEntry {  // recursion detection for SubBody includes (§11.2)
    std::vector<std::string>& chain;
    ChainEntry(std::vector<std::string>& c, std::string path) : chain(c) { chain.push_back(std::move(path)); }
    ~ChainEntry() { chain.pop_back(); }
  } chain_entry(session_.chain, file_identity(file_name));
  struct TextInReach {  // LoadContext::text, for as long as `text` is alive
    LoadContext& ctx;
    TextInReach(LoadContext& c, std::string_view text, const std::string& file) : ctx(c) {
      ctx.text = text;
      ctx.text_file = file;
    }
    ~TextInReach() { ctx.text = {}; }
  } text_in_reach(ctx_, text, file_name);
  Model model;
  model.source_file = file_name;
  model.name = session_.default_model_name.empty() ? std::filesystem::path(file_name).stem().string()
                                                   : session_.default_model_name;
  resources_ = make_resource_handler(options_, ctx_, model, session_);
  std::vector<LinkEntry> entries;

  // Findings wait in the order Choreonoid's reading would make them: the YAML's, the
  // header's, then the links'. Those of links read during the parse are held meanwhile.
  CollectingSink yaml_findings, header_findings, link_findings;
  auto release = [&] {
    for (CollectingSink* held : {&yaml_findings, &header_findings, &link_findings})
      for (Diagnostic& diagnostic : held->diagnostics()) sink_.report(std::move(diagnostic));
    redirect_.redirect(sink_);
  };
  LinkStream link_stream(*this, text, model, entries);
  yaml::ParseOptions parse_options;
  parse_options.max_expanded_nodes = options_.max_expanded_yaml_nodes;
  parse_options.max_depth = options_.max_yaml_depth;
  if (stream) parse_options.stream = &link_stream;
  redirect_.redirect(link_findings);
  auto document = yaml::parse_yaml(text, file_name, parse_options, yaml_findings);
  redirect_.redirect(header_findings);
  if (!document) {
    link_findings.clear();  // a file that does not parse has no links to speak of
    release();
    return std::nullopt;
  }
  resources_->set_main_document(document.get());
  const yaml::NodeRef root = document->root;
  if (!root || !root->is_mapping()) {
    release();
    SourceLocation at{file_name, 1, 1};
    ctx_.report("load-top-level", root ? root.use_site() : at, "the top level of a body file must be a mapping");
    return std::nullopt;
  }
  // The top-level file is the one asked for; an included one is a model once its mapping
  // says so (a file of other keys that a SubBody or a wrapper names is not quoted).
  if (top_level || is_wrapper(*root) || root->find("format") || root->find("links"))
    note_model_text(options_, file_name);
  model.source = root->location;
  documents_.push_back(std::move(document));
  if (is_wrapper(*root)) {
    release();
    std::optional<Model> wrapped = read_wrapper(options_, ctx_, session_, root, file_name);
    if (wrapped && top_level && options_.load_meshes) import_meshes(*wrapped);
    return wrapped;
  }
  const bool header_read = read_header(ctx_, root, model);
  const yaml::MapEntry* links = root->find("links");
  if (header_read && (!link_stream.matches(links ? links->value : yaml::NodeRef{}, model, ctx_) ||
                      resources_->read_yaml_without_main_document())) {
    read_again = true;
    return std::nullopt;
  }
  if (!header_read) link_findings.clear();  // Choreonoid stops before the links
  release();
  if (!header_read) return std::nullopt;

  MappingReader r(ctx_, root, "body");
  for (std::string_view key : body_key_names("body")) r.ignore(key);
  for (std::string_view key : kKnownInfoKeys) r.ignore(key);
  for (const char* key : {"formatVersion", "angleUnit", "rootLink", "extraJoints", "modelFile"}) r.ignore(key);

  if (!links) {
    ctx_.report("load-no-links", root.use_site(), "there is no \"links\" key defining the links of the body");
    return std::nullopt;
  }
  if (link_stream.taken() > 0) {
    for (const yaml::NodeRef& item : links->value->items()) read_link_item(item, model, entries);
  } else {
    read_links(links->value, model, entries);
  }
  if (model.links.empty()) {
    ctx_.report("load-no-links", links->value.use_site(), "no link is defined");
    return std::nullopt;
  }
  // take() warns about the camelCase spellings, like the other header keys (§14).
  if (!build_tree(model, entries, r.take({"root_link", "rootLink"}))) return std::nullopt;
  if (yaml::NodeRef extra = r.take({"extra_joints", "extraJoints"})) read_extra_joints(extra, model);
  r.report_unknown(body_key_names("body"));
  report_upgrade(model);
  if (top_level && options_.load_meshes) import_meshes(model);
  return model;
}

void BodyReader::import_meshes(Model& model) {
  session_.meshes.use_file_cache(options_.file_cache);
  // One asset per (file, node, metadata) in the model; the session's cache parses each file once.
  std::map<std::tuple<std::string, std::string, double, bool>, MeshIndex> indices;
  // Choreonoid detaches every node a body selects from a file out of that file's shared
  // scene, so a selected node never shows up inside another selection (Tank's TURRET_Y
  // does not contain TURRET_P).
  std::map<std::string, std::vector<std::string>> selected_nodes;
  for (const Link& link : model.links)
    for (const Shape& shape : link.shapes)
      if (const auto* mesh = geometry_if<MeshResource>(shape.geometry); mesh && !mesh->node.empty()) {
        auto& names = selected_nodes[mesh->resolved_path];
        if (std::find(names.begin(), names.end(), mesh->node) == names.end()) names.push_back(mesh->node);
      }
  for (Link& link : model.links) {
    for (Shape& shape : link.shapes) {
      auto* mesh = geometry_if<MeshResource>(shape.geometry);
      if (!mesh || mesh->mesh >= 0 || mesh->resolved_path.empty()) continue;
      auto key = std::make_tuple(mesh->resolved_path, mesh->node, mesh->length_scale, mesh->y_up);
      if (auto it = indices.find(key); it != indices.end()) {
        mesh->mesh = it->second;
        continue;
      }
      MeshImportOptions import_options;
      import_options.node = mesh->node;
      import_options.length_scale = mesh->length_scale;
      import_options.y_up = mesh->y_up;
      import_options.max_file_bytes = options_.max_file_bytes;
      import_options.max_triangles = options_.max_mesh_triangles;
      if (auto it = selected_nodes.find(mesh->resolved_path); it != selected_nodes.end())
        import_options.detached_nodes = it->second;
      // Problems with the file point at the `uri:` value that names it.
      const SourceLocation& where = mesh->uri_source.known() ? mesh->uri_source : shape.source;
      auto asset = session_.meshes.get(mesh->resolved_path, import_options, ctx_.sink, where);
      MeshIndex index = -1;
      if (asset) {
        index = static_cast<MeshIndex>(model.meshes.size());
        model.meshes.push_back(*asset);
      }
      indices.emplace(key, index);
      mesh->mesh = index;
    }
  }
}

void BodyReader::report_upgrade(const Model& model) {
  if (model.format_version >= 2.0 || !version_node_) return;
  std::vector<FixIt> fixes;
  std::string problem;
  if (auto fix = edit_value(*version_node_, "2.0", FixSafety::kUpgrade))
    fixes.push_back(std::move(*fix));
  else
    problem = "its format_version value is not written as a plain number";
  if (!ctx_.degrees) {
    if (auto fix = edit_value(*unit_node_, "degree", FixSafety::kUpgrade))
      fixes.push_back(std::move(*fix));
    else
      problem = "its angle_unit value is not written as plain text";
  }
  if (!ctx_.upgrade_blockers.empty()) {
    const SourceLocation& at = ctx_.upgrade_blockers.front();
    problem = "the angle at " + at.file.str() + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) +
              " is not written as a plain number";
  }
  std::string message = "format " + std::string(version_node_->scalar()) + " file";
  if (!ctx_.degrees)
    message += " with angles in radians (" + std::to_string(ctx_.upgrade_fixes.size()) + " angle values)";
  message += "; 2.0 is the current format (snake_case keys, degrees)";
  std::string hint = "bodycheck --fix --upgrade rewrites it as format 2.0";
  if (!problem.empty()) {
    message += "; it cannot be upgraded automatically: " + problem;
    hint.clear();
    fixes.clear();
  } else {
    fixes.insert(fixes.end(), ctx_.upgrade_fixes.begin(), ctx_.upgrade_fixes.end());
  }
  ctx_.report("load-format-upgrade", version_node_, std::move(message), std::move(hint), std::move(fixes));
}

bool BodyReader::read_header(LoadContext& ctx, const yaml::NodeRef& root, Model& model) {
  MappingReader r(ctx, root, "body");
  yaml::NodeRef format = r.take({"format"});
  if (!format) {
    // A wrapper (§2.4) is read by read_wrapper; only the streamed links' silent probe comes here.
    if (!r.has({"model_file", "modelFile"}))
      ctx.report("load-format", root.use_site(), "neither format nor model_file is specified",
                 "add format: ChoreonoidBody");
    return false;
  }
  if (format->scalar() != "ChoreonoidBody") {
    ctx.report("load-format", format.use_site(),
               "the format \"" + std::string(format->scalar()) + "\" cannot be loaded as a Choreonoid body model");
    return false;
  }
  yaml::NodeRef version = r.take({"format_version", "formatVersion"});
  if (!version) {
    ctx.report("load-format-version", root.use_site(),
               "the version of the Choreonoid body file format is not specified", "add format_version: 2.0");
    return false;
  }
  auto v = required_double(ctx, version);
  if (!v) return false;
  if (*v >= 2.1) {
    ctx.report("load-format-version", version.use_site(),
               "version " + std::string(version->scalar()) + " of the Choreonoid body format is not supported");
    return false;
  }
  model.format_version = *v;
  version_node_ = version;
  // The header alone decides the unit: the streamed links' probe may have left radians in
  // ctx from an angle_unit that a later one overrides (the last key wins).
  ctx.degrees = true;
  if (auto unit = r.take({"angle_unit", "angleUnit"})) {
    unit_node_ = unit;
    if (unit->scalar() == "radian") {
      if (*v >= 2.0) {
        // body-format-spec §2.1: radian mode is rejected in format 2.0.
        ctx.report("units-radian-in-2.0", unit.use_site(), "radian mode is not supported in format version 2.0",
                   "write angles in degrees, or use format_version: 1.0");
        return false;
      }
      ctx.degrees = false;
    } else if (unit->scalar() != "degree") {
      ctx.report("load-angle-unit", unit.use_site(), "the angle_unit value must be either \"radian\" or \"degree\"");
      return false;
    }
  }
  model.angles_in_degrees = ctx.degrees;
  if (auto name = r.take({"name"})) model.name = name->scalar();
  if (auto handlers = r.take({"body_handlers"})) {
    if (handlers->is_scalar())
      model.body_handlers.emplace_back(handlers->scalar());
    else if (handlers->is_sequence())
      for (const auto& h : handlers->items())
        if (h->is_scalar()) model.body_handlers.emplace_back(h->scalar());
  }
  return true;
}

void BodyReader::read_link_node(const yaml::NodeRef& node, const std::string& type, Model& model,
                                std::vector<LinkEntry>& entries) {
  if (!node->is_mapping()) {
    ctx_.report("load-type", node, "a link must be a mapping");
    return;
  }
  if (type == "Skip") return;
  if (type.empty() || type == "Link") {
    entries.push_back(read_link(ctx_, node, model, resources_.get()));
    return;
  }
  if (type == "SubBody" || type == "ContinuousTrack") {
    resources_->read_link_node(node, type, entries);
    return;
  }
  ctx_.report("load-link-type", node, "a " + type + " node cannot be specified in links",
              "use Link, SubBody, ContinuousTrack or Skip");
}

void BodyReader::read_link_item(const yaml::NodeRef& item, Model& model, std::vector<LinkEntry>& entries) {
  const yaml::MapEntry* type = item->is_mapping() ? item->find("type") : nullptr;
  read_link_node(item, type ? std::string(type->value->scalar()) : std::string(), model, entries);
}

void BodyReader::read_links(const yaml::NodeRef& links, Model& model, std::vector<LinkEntry>& entries) {
  if (links->is_sequence()) {
    // One Link per item in the common case (SubBodies add more): no growth by reallocation,
    // which would keep the old and the new link arrays alive together.
    model.links.reserve(links->items().size());
    entries.reserve(links->items().size());
    if (links->items().empty()) ctx_.report("load-no-links", links, "no link is contained in the \"links\" listing");
    for (const yaml::NodeRef& item : links->items()) read_link_item(item, model, entries);
  } else if (links->is_mapping()) {
    std::vector<const yaml::MapEntry*> sorted;
    for (const auto& e : links->entries()) sorted.push_back(&e);
    std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->key < b->key; });
    for (const yaml::MapEntry* e : sorted) {
      // As for elements: Choreonoid's readNodeInLinks refuses an inner type other than the key.
      if (const yaml::MapEntry* inner = e->value->is_mapping() ? e->value->find("type") : nullptr;
          inner && inner->value->scalar() != e->key) {
        ctx_.report("load-type-mismatch", links.child(inner->value),
                    "the node type \"" + std::string(inner->value->scalar()) + "\" is different from the type \"" +
                        std::string(e->key) + "\" specified in the parent node");
        continue;
      }
      read_link_node(links.child(e->value), std::string(e->key), model, entries);
    }
  } else {
    ctx_.report("load-no-links", links, "invalid value specified in the \"links\" key");
  }
}

namespace {

using Index = std::size_t;
Index at(LinkIndex i) { return static_cast<Index>(i); }

/// The roots of the trees the parent links accepted so far form, kept in a union-find so
/// that each cycle check is near O(1): a link gets a parent once, while it is still the root
/// of its own tree, so adding it under `p` closes a cycle exactly when `p`'s root is the link.
class TreeRoots {
 public:
  explicit TreeRoots(std::size_t n) : set_(n), size_(n, 1), root_(n) {
    for (Index i = 0; i < n; ++i) set_[i] = root_[i] = static_cast<LinkIndex>(i);
  }
  LinkIndex root_of(LinkIndex i) { return root_[at(find(i))]; }
  /// Records `child` (a tree root) under `parent`.
  void attach(LinkIndex child, LinkIndex parent) {
    LinkIndex a = find(child), b = find(parent);
    const LinkIndex root = root_[at(b)];
    if (size_[at(a)] > size_[at(b)]) std::swap(a, b);
    set_[at(a)] = b;
    size_[at(b)] += size_[at(a)];
    root_[at(b)] = root;
  }

 private:
  LinkIndex find(LinkIndex i) {
    LinkIndex r = i;
    while (set_[at(r)] != r) r = set_[at(r)];
    while (set_[at(i)] != r) i = std::exchange(set_[at(i)], r);
    return r;
  }
  std::vector<LinkIndex> set_;
  std::vector<std::size_t> size_;
  std::vector<LinkIndex> root_;
};

/// `"A"`, `"A" or "B"`, `"A", "B" or "C"`: the first three names, for a did-you-mean.
std::string quoted_alternatives(const std::vector<std::string_view>& names) {
  const std::size_t n = std::min<std::size_t>(names.size(), 3);
  std::string out;
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) out += k + 1 == n ? " or " : ", ";
    out += "\"" + std::string(names[k]) + "\"";
  }
  return out;
}

/// A name that reads back the same written in place of a plain or a quoted scalar.
bool writable_in_place(std::string_view name) {
  if (name.empty() || !(std::isalnum(static_cast<unsigned char>(name.front())) || name.front() == '_')) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

/// Depth-first pre-order from the root, children in definition order (§5.2).
std::vector<LinkIndex> depth_first_order(LinkIndex root, const std::vector<std::vector<LinkIndex>>& children) {
  std::vector<LinkIndex> order;
  std::vector<LinkIndex> stack{root};
  while (!stack.empty()) {
    const LinkIndex i = stack.back();
    stack.pop_back();
    order.push_back(i);
    const auto& c = children[at(i)];
    for (auto it = c.rbegin(); it != c.rend(); ++it) stack.push_back(*it);
  }
  return order;
}

}  // namespace

BodyReader::LinkNames BodyReader::index_link_names(const Model& model, const std::vector<LinkEntry>& entries) {
  LinkNames names{NameIndex(model.links.size()), NameIndex()};
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(model.links.size()); ++i) {
    const Link& link = model.links[at(i)];
    // A ContinuousTrack's own name, registered before its first link's (as Choreonoid does).
    if (const LinkEntry& entry = entries[at(i)]; !entry.alias.empty()) {
      if (auto first = names.by_name.insert(entry.alias, i)) {
        ctx_.report("structure-duplicate-link", entry.alias_site,
                    "duplicated link name \"" + entry.alias + "\" (first defined at line " +
                        std::to_string(model.links[at(*first)].sources.name().line) + ")");
      }
    }
    if (link.name.empty()) continue;
    if (auto first = names.by_name.insert(link.name, i)) {
      ctx_.report("structure-duplicate-link", link.sources.name(),
                  "duplicated link name \"" + link.name + "\" (first defined at line " +
                      std::to_string(model.links[at(*first)].sources.name().line) + ")");
    }
    // The links of one ContinuousTrack node share its joint name (load-track-shared-joint).
    if (link.joint_name.empty()) continue;
    if (auto first = names.by_joint_name.insert(link.joint_name, i);
        first && model.links[at(*first)].source != link.source)
      ctx_.report("structure-duplicate-joint-name", link.source, "duplicated joint name \"" + link.joint_name + "\"");
  }
  return names;
}

std::vector<LinkIndex> BodyReader::link_parents(const Model& model, const std::vector<LinkEntry>& entries,
                                                const LinkNames& names, LinkIndex root) {
  const std::size_t n = model.links.size();
  std::vector<LinkIndex> parent(n, -1);
  TreeRoots roots(n);
  std::vector<std::string_view> known;  // the defined names in order, for did-you-mean hints
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(n); ++i) {
    const Link& link = model.links[at(i)];
    const LinkEntry& entry = entries[at(i)];
    if (i == root) {
      if (!entry.parent_name.empty())
        ctx_.report("structure-root-parent", link.sources.parent(),
                    "the root link \"" + link.name + "\" must not have a parent");
      continue;
    }
    if (entry.parent_name.empty()) {
      ctx_.report("structure-no-parent", link.source, "the parent of link \"" + link.name + "\" is not specified",
                  "add parent: PARENT_LINK");
      continue;
    }
    const std::optional<LinkIndex> found = names.by_name.find(entry.parent_name);
    if (!found) {
      if (known.empty()) {
        known = names.by_name.names();
        std::sort(known.begin(), known.end());
      }
      // Every name as near as the nearest is offered; the rename is a fix-it when one is.
      // It is unsafe: the link is then attached, so the model changes.
      const std::vector<std::string_view> nearest = text::nearest(entry.parent_name, known);
      const std::string names = quoted_alternatives(nearest);
      std::vector<FixIt> fixes;
      if (nearest.size() == 1 && entry.parent_span.editable() && writable_in_place(nearest.front())) {
        FixIt fix;
        fix.file = entry.parent_site.file;
        fix.begin = entry.parent_span.begin;
        fix.end = entry.parent_span.end;
        fix.line = entry.parent_site.line;
        fix.column = entry.parent_span.column;
        fix.original = entry.parent_name;
        fix.replacement = std::string(nearest.front());
        fix.safety = FixSafety::kUnsafe;
        fixes.push_back(std::move(fix));
      }
      ctx_.report("structure-unknown-parent", entry.parent_site,
                  "parent link \"" + entry.parent_name + "\" of \"" + link.name + "\" is not defined" +
                      (nearest.empty() ? std::string() : "; did you mean " + names + "?"),
                  nearest.empty() ? std::string() : "name a link that is defined: " + names, std::move(fixes));
      continue;
    }
    // A parent chain that comes back to this link is a cycle (§5.2).
    if (roots.root_of(*found) == i) {
      ctx_.report("structure-cycle", entry.parent_site,
                  "adding \"" + link.name + "\" to link \"" + entry.parent_name + "\" would make a cycle");
      continue;
    }
    if (model.links[at(*found)].name != entry.parent_name) track_name_used(model, *found, entry.parent_site);
    parent[at(i)] = *found;
    roots.attach(i, *found);
  }
  return parent;
}

void BodyReader::reorder_links(Model& model, const std::vector<LinkIndex>& order, const std::vector<LinkIndex>& parent,
                               std::vector<std::vector<LinkIndex>>& children) {
  std::vector<LinkIndex> new_index(model.links.size(), -1);
  for (std::size_t k = 0; k < order.size(); ++k) new_index[at(order[k])] = static_cast<LinkIndex>(k);
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(model.links.size()); ++i) {
    if (new_index[at(i)] < 0 && parent[at(i)] >= 0) {
      const Link& link = model.links[at(i)];
      ctx_.report(
          "structure-unreachable", link.source,
          "link \"" + link.name + "\" is not connected to the root link \"" + model.links[at(order[0])].name + "\"");
    }
  }
  // Parents and children in the new numbering, then the links permuted in place (following
  // the permutation's cycles), so that no second copy of the link vector is ever alive.
  std::vector<std::size_t> target(model.links.size());
  std::size_t dropped = order.size();
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(model.links.size()); ++i) {
    Link& link = model.links[at(i)];
    if (new_index[at(i)] < 0) {
      target[at(i)] = dropped++;  // unreachable: moved past the end, then erased
      continue;
    }
    target[at(i)] = at(new_index[at(i)]);
    const LinkIndex p = parent[at(i)];
    link.parent = p >= 0 ? new_index[at(p)] : -1;
    link.children = std::move(children[at(i)]);
    for (LinkIndex& c : link.children) c = new_index[at(c)];
  }
  for (std::size_t i = 0; i < target.size(); ++i) {
    while (target[i] != i) {
      const std::size_t j = target[i];
      std::swap(model.links[i], model.links[j]);
      std::swap(target[i], target[j]);
    }
  }
  model.links.erase(model.links.begin() + static_cast<std::ptrdiff_t>(order.size()), model.links.end());
  // Devices follow their links; devices of dropped links are dropped with them.
  std::vector<Device> devices;
  for (Device& d : model.devices) {
    const LinkIndex k = new_index[at(d.link)];
    if (k < 0) continue;
    d.link = k;
    devices.push_back(std::move(d));
  }
  std::stable_sort(devices.begin(), devices.end(), [](const Device& a, const Device& b) { return a.link < b.link; });
  model.devices = std::move(devices);
  // Extra joints carried over from SubBodies follow their links too, and go with them when a
  // link is dropped (already reported as structure-unreachable).
  std::vector<ExtraJoint> extra_joints;
  for (ExtraJoint& j : model.extra_joints) {
    const LinkIndex l1 = j.link1 >= 0 ? new_index[at(j.link1)] : -1;
    const LinkIndex l2 = j.link2 >= 0 ? new_index[at(j.link2)] : -1;
    if (l1 < 0 || l2 < 0) continue;
    j.link1 = l1;
    j.link2 = l2;
    extra_joints.push_back(std::move(j));
  }
  model.extra_joints = std::move(extra_joints);
}

void BodyReader::track_name_used(const Model& model, LinkIndex link, const SourceLocation& where) {
  const std::string& name = model.links[at(link)].name;
  ctx_.report("load-track-name", where,
              "\"" + name.substr(0, name.size() - 1) +
                  "\" names a ContinuousTrack node: Choreonoid takes it as its "
                  "first link \"" +
                  name + "\"",
              "write " + name);
}

bool BodyReader::build_tree(Model& model, const std::vector<LinkEntry>& entries, const yaml::NodeRef& root_link) {
  const LinkNames names = index_link_names(model, entries);
  LinkIndex root = 0;
  if (root_link) {
    const std::optional<LinkIndex> found = names.by_name.find(root_link->scalar());
    if (!found) {
      ctx_.report("structure-root-link", root_link.use_site(),
                  "link \"" + std::string(root_link->scalar()) + "\" specified in root_link is not defined");
      return false;
    }
    if (model.links[at(*found)].name != root_link->scalar()) track_name_used(model, *found, root_link.use_site());
    root = *found;
  }
  const std::vector<LinkIndex> parent = link_parents(model, entries, names, root);
  std::vector<std::vector<LinkIndex>> children(model.links.size());
  for (LinkIndex i = 0; i < static_cast<LinkIndex>(model.links.size()); ++i)
    if (parent[at(i)] >= 0) children[at(parent[at(i)])].push_back(i);
  reorder_links(model, depth_first_order(root, children), parent, children);
  return true;
}

void BodyReader::read_extra_joints(const yaml::NodeRef& extra_joints, Model& model) {
  if (!extra_joints->is_sequence()) {
    ctx_.report("load-ignored-value", extra_joints, "extra_joints must be a sequence; Choreonoid ignores it");
    return;
  }
  for (const yaml::NodeRef& node : extra_joints->items()) {
    if (!node->is_mapping()) {
      ctx_.report("load-type", node, "an extra joint must be a mapping");
      continue;
    }
    MappingReader r(ctx_, node, "extra joint");
    ExtraJoint joint;
    joint.source = node.use_site();
    bool ok = true;
    for (int k = 1; k <= 2; ++k) {
      const std::string snake = k == 1 ? "link1_name" : "link2_name";
      yaml::NodeRef name = k == 1 ? r.take({"link1_name", "link1Name"}) : r.take({"link2_name", "link2Name"});
      if (!name) {
        ctx_.report("extra-joint-link", node, snake + " is not specified");
        ok = false;
        continue;
      }
      LinkIndex index = model.find_link(name->scalar());
      if (index < 0) {
        ctx_.report("extra-joint-link", name,
                    "the link \"" + std::string(name->scalar()) + "\" specified in " + snake + " is not found");
        ok = false;
      }
      (k == 1 ? joint.link1 : joint.link2) = index;
    }
    yaml::NodeRef type = r.take({"joint_type", "jointType"});
    if (!type) {
      ctx_.report("extra-joint-type", node, "the joint type must be specified with the \"joint_type\" key");
      ok = false;
    } else if (type->scalar() != "fixed" && type->scalar() != "hinge" && type->scalar() != "ball" &&
               type->scalar() != "piston") {
      ctx_.report("extra-joint-type", type, "joint type \"" + std::string(type->scalar()) + "\" is not available",
                  "use fixed, hinge, ball or piston");
      ok = false;
    } else {
      joint.type = type->scalar();
    }
    if (auto axis = r.take({"axis", "jointAxis"}); axis && (joint.type == "fixed" || joint.type == "ball")) {
      // readExtraJoint reads the axis of a hinge or a piston only.
      ctx_.report("load-ignored-key", axis, "a " + joint.type + " extra joint has no axis; Choreonoid does not read it",
                  "remove it");
    } else if (axis) {
      if (auto a = read_vec3(ctx_, axis)) {
        if (a->norm() > 0)
          joint.axis = a->normalized();
        else
          ctx_.report("extra-joint-axis", axis, "the extra joint axis is the zero vector");
      }
    }
    if (auto t = r.take({"translation_in_link1", "link1LocalPos"}))
      if (auto v = read_vec3(ctx_, t)) joint.X_1J.translation() = *v;
    if (auto t = r.take({"translation_in_link2", "link2LocalPos"}))
      if (auto v = read_vec3(ctx_, t)) joint.X_2J.translation() = *v;
    if (auto rot = r.take({"rotation_in_link1"}))
      if (auto R = read_rotation(ctx_, rot)) joint.X_1J.linear() = *R;
    if (auto rot = r.take({"rotation_in_link2"}))
      if (auto R = read_rotation(ctx_, rot)) joint.X_2J.linear() = *R;
    for (const char* ignored : {"link1_local_pos", "link2_local_pos"}) {
      if (auto v = r.take({ignored}))
        ctx_.report("load-ignored-key", v, std::string("Choreonoid does not read \"") + ignored + "\"",
                    std::string("use translation_in_link") + ignored[4]);
    }
    r.report_unknown(body_key_names("extra_joint"));
    if (ok) model.extra_joints.push_back(joint);
  }
}

}  // namespace bodyfmt::detail
