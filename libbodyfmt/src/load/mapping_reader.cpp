#include "load/mapping_reader.h"

#include "load/scalar.h"
#include "text/text_util.h"

#include <algorithm>
#include <cctype>

namespace bodyfmt::detail {
namespace {

/// Calls `f` with each '\0'-terminated name of `buffer`, in order, until it returns true.
template <typename F>
bool any_name(std::string_view buffer, F f) {
  for (std::size_t begin = 0; begin < buffer.size();) {
    const std::size_t end = buffer.find('\0', begin);
    if (f(buffer.substr(begin, end - begin))) return true;
    begin = end + 1;
  }
  return false;
}

void append_name(std::string& buffer, std::string_view name) {
  buffer.append(name);
  buffer.push_back('\0');
}

}  // namespace

MappingReader::MappingReader(LoadContext& ctx, const yaml::NodeRef& mapping, std::string what)
    : ctx_(ctx), mapping_(mapping), what_(std::move(what)) {}

yaml::NodeRef MappingReader::take(KeyNames names) {
  if (!mapping_ || !mapping_->is_mapping()) return {};
  bool modern = true;
  for (std::string_view name : names) {
    if (name != *names.begin() && modern_of(name).empty()) {
      append_name(legacy_, name);
      append_name(legacy_, *names.begin());
    }
  }
  for (std::string_view name : names) {
    if (const yaml::MapEntry* entry = mapping_->find(name)) {
      if (!consumed(name)) append_name(consumed_, name);
      if (!modern) {
        // Located at the key: that is the text to change. Take() found no earlier spelling in
        // this mapping, so the rename cannot collide with a key already there.
        const std::string modern_name(*names.begin());
        std::vector<FixIt> fixes;
        if (auto fix = edit_key(*entry, modern_name, FixSafety::kSafe)) fixes.push_back(std::move(*fix));
        ctx_.report("load-legacy-key", entry->key_location,
                    "legacy key \"" + std::string(name) + "\"; the modern spelling is \"" + modern_name + "\"",
                    "rename it to " + modern_name, std::move(fixes));
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

void MappingReader::ignore(std::string_view name) {
  if (!consumed(name)) append_name(consumed_, name);
}

bool MappingReader::consumed(std::string_view key) const {
  return any_name(consumed_, [&](std::string_view name) { return name == key; });
}

std::string_view MappingReader::modern_of(std::string_view legacy) const {
  std::string_view modern;
  bool is_legacy = true;  // names alternate: legacy, modern, legacy, ...
  bool found = false;
  any_name(legacy_, [&](std::string_view name) {
    if (!is_legacy && found) {
      modern = name;
      return true;
    }
    found = is_legacy && name == legacy;
    is_legacy = !is_legacy;
    return false;
  });
  return modern;
}

bool MappingReader::unique_guess(std::string_view key, const std::vector<std::string_view>& candidates,
                                 std::string_view guess) const {
  const int best = text::edit_distance(key, guess);
  for (std::string_view candidate : candidates) {
    std::string_view modern = modern_of(candidate);
    if (modern.empty()) modern = candidate;
    if (modern != guess && text::edit_distance(key, candidate) <= best) return false;
  }
  return true;
}

bool MappingReader::has_spelling_of(std::string_view modern) const {
  std::string_view legacy;
  bool is_legacy = true;
  return any_name(legacy_, [&](std::string_view name) {
    const bool match = !is_legacy && name == modern && mapping_->find(legacy);
    if (is_legacy) legacy = name;
    is_legacy = !is_legacy;
    return match;
  });
}

void MappingReader::report_unknown(const std::vector<std::string_view>& known) {
  if (!mapping_ || !mapping_->is_mapping()) return;
  // Legacy spellings are candidates too (a typo of `jointRange` is closer to it than to
  // `joint_range`); the hint then names the modern spelling.
  std::vector<std::string_view> candidates;
  for (const yaml::MapEntry& entry : mapping_->entries) {
    if (consumed(entry.key) || entry.merged) continue;
    if (candidates.empty()) {  // built for the first unknown key only: most mappings have none
      candidates = known;
      std::vector<std::string_view> legacy;  // sorted, so that ties between guesses break alike
      bool is_legacy = true;
      any_name(legacy_, [&](std::string_view name) {
        if (is_legacy) legacy.push_back(name);
        is_legacy = !is_legacy;
        return false;
      });
      std::sort(legacy.begin(), legacy.end());
      candidates.insert(candidates.end(), legacy.begin(), legacy.end());
    }
    std::string_view guess = text::suggest(entry.key, candidates);
    if (std::string_view modern = modern_of(guess); !modern.empty()) guess = modern;
    if (!guess.empty()) {
      // The rename is a fix-it only when the guess is the one candidate that close and no
      // spelling of it is in the mapping already; it is unsafe: the value is then read.
      std::vector<FixIt> fixes;
      if (unique_guess(entry.key, candidates, guess) && !mapping_->find(guess) && !has_spelling_of(guess))
        if (auto fix = edit_key(entry, std::string(guess), FixSafety::kUnsafe)) fixes.push_back(std::move(*fix));
      ctx_.report("load-unknown-key", entry.key_location,
                  "unknown key \"" + entry.key + "\" in " + what_ + "; did you mean \"" + std::string(guess) + "\"?",
                  "Choreonoid ignores it; rename it to " + std::string(guess), std::move(fixes));
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

std::optional<double> take_optional_angle(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  auto value = optional_double(r.context(), ref);
  if (!value) return std::nullopt;
  return r.context().angle(*value, ref);
}

std::optional<bool> take_optional_bool(MappingReader& r, KeyNames names) {
  yaml::NodeRef ref = r.take(names);
  if (!ref) return std::nullopt;
  return optional_bool(r.context(), ref);
}

}  // namespace bodyfmt::detail
