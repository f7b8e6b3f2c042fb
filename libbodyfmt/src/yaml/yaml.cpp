// The public YAML API (bodyfmt/yaml.h) over the library's own YAML tree (yaml/yaml_node.h),
// which stays private, and the bounded file reader (bodyfmt/read_file.h).

#include <bodyfmt/rules.h>
#include <bodyfmt/yaml.h>

#include <bodyfmt/read_file.h>
#include "text/number_text.h"
#include "text/text_util.h"
#include "yaml/yaml_node.h"

#include <cmath>
#include <utility>

namespace bodyfmt {

struct YamlDocument::Impl {
  std::unique_ptr<yaml::Document> document;
};

struct YamlNodeAccess {
  static YamlNode make(const yaml::NodeRef& ref) {
    YamlNode node;
    node.node_ = ref.node;
    // use_site() is the alias or the node's own location, both in the document: stable.
    node.site_ = ref.node != nullptr ? &ref.use_site() : nullptr;
    return node;
  }
  static const yaml::Node* node(const YamlNode& node) { return static_cast<const yaml::Node*>(node.node_); }
  static YamlDocument document(std::unique_ptr<yaml::Document> document) {
    return YamlDocument(std::make_unique<YamlDocument::Impl>(YamlDocument::Impl{std::move(document)}));
  }
};

namespace {

const yaml::Node* node_of(const YamlNode& node) { return YamlNodeAccess::node(node); }

}  // namespace

bool YamlNode::is_scalar() const { return node_ != nullptr && node_of(*this)->is_scalar(); }
bool YamlNode::is_sequence() const { return node_ != nullptr && node_of(*this)->is_sequence(); }
bool YamlNode::is_mapping() const { return node_ != nullptr && node_of(*this)->is_mapping(); }
bool YamlNode::is_null() const { return node_ != nullptr && node_of(*this)->is_null(); }
std::string_view YamlNode::scalar() const { return node_ != nullptr ? node_of(*this)->scalar() : std::string_view(); }

const SourceLocation& YamlNode::location() const {
  static const SourceLocation kNowhere;
  return site_ != nullptr ? *site_ : kNowhere;
}

std::vector<YamlNode> YamlNode::items() const {
  std::vector<YamlNode> out;
  if (!is_sequence()) return out;
  out.reserve(node_of(*this)->items().size());
  for (const yaml::NodeRef& item : node_of(*this)->items()) out.push_back(YamlNodeAccess::make(item));
  return out;
}

std::vector<YamlEntry> YamlNode::entries() const {
  std::vector<YamlEntry> out;
  if (!is_mapping()) return out;
  out.reserve(node_of(*this)->entries().size());
  for (const yaml::MapEntry& entry : node_of(*this)->entries())
    out.push_back(YamlEntry{entry.key, entry.key_location, YamlNodeAccess::make(entry.value)});
  return out;
}

std::optional<YamlEntry> YamlNode::find(std::string_view key) const {
  if (!is_mapping()) return std::nullopt;
  const yaml::MapEntry* entry = node_of(*this)->find(key);
  if (entry == nullptr) return std::nullopt;
  return YamlEntry{entry->key, entry->key_location, YamlNodeAccess::make(entry->value)};
}

YamlDocument::YamlDocument(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
YamlDocument::YamlDocument(YamlDocument&&) noexcept = default;
YamlDocument& YamlDocument::operator=(YamlDocument&&) noexcept = default;
YamlDocument::~YamlDocument() = default;

YamlNode YamlDocument::root() const { return YamlNodeAccess::make(impl_->document->root); }
const std::string& YamlDocument::file() const { return impl_->document->file; }

std::optional<YamlDocument> parse_yaml_text(std::string_view text, const std::string& file_name, DiagnosticSink& sink,
                                            const YamlLimits& limits) {
  yaml::ParseOptions options;
  options.max_expanded_nodes = limits.max_expanded_nodes;
  options.max_depth = limits.max_depth;
  std::unique_ptr<yaml::Document> document = yaml::parse_yaml(text, file_name, options, sink);
  if (!document) return std::nullopt;
  return YamlNodeAccess::document(std::move(document));
}

std::optional<YamlDocument> read_yaml_file(const std::string& path, DiagnosticSink& sink, const YamlLimits& limits,
                                           std::string_view what) {
  std::string why;
  const std::optional<detail::FileBytes> bytes = detail::read_regular_file_bytes(path, limits.max_file_bytes, why);
  if (!bytes) {
    const std::string name = what.empty() ? "\"" + path + "\"" : std::string(what);
    report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "cannot read " + name + ": " + why);
    return std::nullopt;
  }
  return parse_yaml_text(bytes->view(), path, sink, limits);
}

YamlReader::YamlReader(DiagnosticSink& sink, std::string rule_id) : sink_(sink), rule_id_(std::move(rule_id)) {}

void YamlReader::error(const SourceLocation& at, std::string message, std::string hint) {
  report_rule(sink_, rule_id_, at, std::move(message), std::move(hint));
  ok_ = false;
}

bool YamlReader::mapping(const YamlNode& node, std::string_view what) {
  if (node.is_mapping()) return true;
  error(node, std::string(what) + " must be a mapping");
  return false;
}

bool YamlReader::sequence(const YamlNode& node, std::string_view what) {
  if (node.is_sequence()) return true;
  error(node, std::string(what) + " must be a list");
  return false;
}

std::optional<std::string_view> YamlReader::scalar(const YamlNode& node, std::string_view what) {
  if (node.is_scalar()) return node.scalar();
  error(node, std::string(what) + " must be a single value, not a list or a mapping");
  return std::nullopt;
}

std::optional<double> YamlReader::number(const YamlNode& node, std::string_view what) {
  // The scalar is NUL-terminated in the document's arena, as parse_double_exact needs.
  std::optional<double> value = node.is_scalar() ? detail::parse_double_exact(node.scalar()) : std::nullopt;
  if (!value || !std::isfinite(*value)) {
    error(node, std::string(what) + " must be a number");
    return std::nullopt;
  }
  return value;
}

std::optional<bool> YamlReader::boolean(const YamlNode& node, std::string_view what) {
  std::optional<bool> value = node.is_scalar() ? text::parse_bool_word(node.scalar()) : std::nullopt;
  if (!value) error(node, std::string(what) + " must be true or false");
  return value;
}

bool YamlReader::known_keys(const YamlNode& mapping, const std::vector<std::string_view>& keys, std::string_view what) {
  const std::vector<YamlEntry> unknown = unknown_keys(mapping, keys);
  if (unknown.empty()) return true;
  std::string list;
  for (std::string_view key : keys) list += (list.empty() ? "" : ", ") + std::string(key);
  for (const YamlEntry& entry : unknown) {
    std::string message = "unknown key '" + std::string(entry.key) + "' in " + std::string(what);
    if (std::string_view guess = did_you_mean(entry.key, keys); !guess.empty())
      message += "; did you mean '" + std::string(guess) + "'?";
    error(entry.key_location, std::move(message), "keys: " + list);
  }
  return false;
}

std::vector<YamlEntry> unknown_keys(const YamlNode& mapping, const std::vector<std::string_view>& keys) {
  std::vector<YamlEntry> out;
  for (YamlEntry& entry : mapping.entries()) {
    bool known = false;
    for (std::string_view key : keys) known = known || entry.key == key;
    if (!known) out.push_back(std::move(entry));
  }
  return out;
}

std::string_view did_you_mean(std::string_view word, const std::vector<std::string_view>& candidates) {
  return text::suggest(word, candidates);
}

}  // namespace bodyfmt
