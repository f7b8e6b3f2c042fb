#include "load/mapping_reader.h"

#include "load/scalar.h"
#include "text/text_util.h"

#include <algorithm>
#include <cctype>

namespace bodyfmt::detail {

MappingReader::MappingReader(LoadContext& ctx, const yaml::NodeRef& mapping, std::string what)
    : ctx_(ctx), mapping_(mapping), what_(std::move(what)) {}

yaml::NodeRef MappingReader::take(KeyNames names) {
  if (!mapping_ || !mapping_->is_mapping()) return {};
  bool modern = true;
  for (std::string_view name : names) {
    if (name != *names.begin()) legacy_.emplace(std::string(name), std::string(*names.begin()));
  }
  for (std::string_view name : names) {
    if (const yaml::MapEntry* entry = mapping_->find(name)) {
      consumed_.emplace(name);
      if (!modern) {
        // Located at the key: that is the text to change.
        ctx_.report(
            "load-legacy-key", entry->key_location,
            "legacy key \"" + std::string(name) + "\"; the modern spelling is \"" + std::string(*names.begin()) + "\"",
            "rename it to " + std::string(*names.begin()));
      }
      return mapping_.child(entry->value);
    }
    modern = false;
  }
  return {};
}

bool MappingReader::has(KeyNames names) const {
  if (!mapping_ || !mapping_->is_mapping()) return false;
  return std::any_of(names.begin(), names.end(), [&](std::string_view n) { return mapping_->find(n) != nullptr; });
}

void MappingReader::ignore(std::string_view name) { consumed_.emplace(name); }

void MappingReader::report_unknown(const std::vector<std::string_view>& known) {
  if (!mapping_ || !mapping_->is_mapping()) return;
  // Legacy spellings are candidates too (a typo of `jointRange` is closer to it than to
  // `joint_range`); the hint then names the modern spelling.
  std::vector<std::string_view> candidates = known;
  for (const auto& [legacy, modern] : legacy_) candidates.push_back(legacy);
  for (const yaml::MapEntry& entry : mapping_->entries) {
    if (consumed_.count(entry.key) || entry.merged) continue;
    std::string_view guess = text::suggest(entry.key, candidates);
    if (auto it = legacy_.find(guess); it != legacy_.end()) guess = it->second;
    if (!guess.empty()) {
      ctx_.report("load-unknown-key", entry.key_location,
                  "unknown key \"" + entry.key + "\" in " + what_ + "; did you mean \"" + std::string(guess) + "\"?",
                  "Choreonoid ignores it; rename it to " + std::string(guess));
    } else {
      ctx_.report("load-info-key", entry.key_location,
                  "key \"" + entry.key + "\" is not part of the " + what_ + " format; it is kept as info");
    }
  }
}

std::optional<double> take_optional_double(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return optional_double(r.context(), ref);
}

std::optional<bool> take_optional_bool(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return optional_bool(r.context(), ref);
}

}  // namespace bodyfmt::detail
