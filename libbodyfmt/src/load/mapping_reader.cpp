#include "load/mapping_reader.h"

#include "load/scalar.h"
#include "text/text_util.h"

#include <algorithm>
#include <cctype>

namespace bodyfmt::detail {

MappingReader::MappingReader(LoadContext& ctx, const yaml::NodeRef& mapping, std::string what)
    : ctx_(ctx), mapping_(mapping), what_(std::move(what)) {
  if (mapping_ && mapping_->is_mapping()) {
    if (mapping_->entries().size() > kInlineEntries) consumed_large_.assign(mapping_->entries().size(), false);
    for (const yaml::MapEntry& entry : mapping_->entries()) key_filter_ |= filter_bit(entry.key);
  }
}

void MappingReader::consume(const yaml::MapEntry* entry) {
  const auto i = static_cast<std::size_t>(entry - mapping_->entries().begin());
  if (consumed_large_.empty())
    consumed_small_ |= std::uint64_t{1} << i;
  else
    consumed_large_[i] = true;
}

std::string_view MappingReader::modern_of(std::string_view name) const {
  for (const auto& [legacy, modern] : legacy_)
    if (legacy == name) return modern;
  return {};
}

yaml::NodeRef MappingReader::take(KeyNames names) {
  if (!mapping_ || !mapping_->is_mapping()) return {};
  bool modern = true;
  // Recorded for report_unknown, which drops repeats: a lookup here would cost every take()
  // a scan of the spellings so far.
  for (auto legacy = names.begin(); legacy != names.end(); ++legacy) {
    if (legacy == names.begin()) continue;
    if (legacy_.empty()) legacy_.reserve(32);  // a link's mapping records about twenty spellings
    legacy_.emplace_back(*legacy, *names.begin());
  }
  for (std::string_view name : names) {
    if (const yaml::MapEntry* entry = find(name)) {
      consume(entry);
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
  return std::any_of(names.begin(), names.end(), [&](std::string_view n) { return find(n) != nullptr; });
}

void MappingReader::ignore(std::string_view name) {
  if (!mapping_ || !mapping_->is_mapping()) return;
  if (const yaml::MapEntry* entry = find(name)) consume(entry);
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
  for (const auto& [legacy, name] : legacy_)
    if (name == modern && mapping_->find(legacy)) return true;
  return false;
}

bool MappingReader::has_unknown() const {
  if (!mapping_ || !mapping_->is_mapping()) return false;
  for (std::size_t i = 0; i < mapping_->entries().size(); ++i)
    if (!consumed(i) && !mapping_->entries()[i].merged) return true;
  return false;
}

namespace {

/// Keys whose value changes the model's kinematics, dynamics or collision shapes: a typo of one
/// silently leaves a default in place (a 1 kg link, a joint about Z, an unlimited joint), so it
/// is an error. The modern spellings; legacy ones are mapped to these first.
bool changes_model(std::string_view key) {
  static constexpr std::string_view kModelKeys[] = {"mass",
                                                    "inertia",
                                                    "center_of_mass",
                                                    "translation",
                                                    "rotation",
                                                    "scale",
                                                    "parent",
                                                    "joint_type",
                                                    "joint_axis",
                                                    "joint_range",
                                                    "joint_angle",
                                                    "joint_displacement",
                                                    "max_joint_velocity",
                                                    "joint_velocity_range",
                                                    "max_joint_effort",
                                                    "joint_axis_inertia",
                                                    "rotor_inertia",
                                                    "gear_ratio",
                                                    "elements",
                                                    "geometry",
                                                    "size",
                                                    "radius",
                                                    "height"};
  return std::find(std::begin(kModelKeys), std::end(kModelKeys), key) != std::end(kModelKeys);
}

/// The closest candidate within the typo distance: 1 for words of 4 to 7 characters and 2 from
/// 8, counted on the longer of the two words, so that a dropped letter of a 4-letter key (`mas`)
/// is caught while two 3-letter words are never taken for one another.
std::string_view closest_key(std::string_view key, const std::vector<std::string_view>& candidates) {
  std::string_view best;
  int best_distance = 1 << 30;
  for (std::string_view candidate : candidates) {
    const std::size_t longer = std::max(key.size(), candidate.size());
    const int allowed = longer >= 8 ? 2 : (longer >= 4 ? 1 : 0);
    const int d = text::edit_distance(key, candidate);
    if (d <= allowed && d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

}  // namespace

void MappingReader::report_unknown(const std::vector<std::string_view>& known) {
  if (!has_unknown()) return;
  // Legacy spellings are candidates too (a typo of `jointRange` is closer to it than to
  // `joint_range`); the hint then names the modern spelling.
  std::vector<std::string_view> candidates = known;
  const std::size_t first_legacy = candidates.size();
  for (const auto& [legacy, modern] : legacy_) candidates.push_back(legacy);
  std::sort(candidates.begin() + static_cast<std::ptrdiff_t>(first_legacy), candidates.end());  // as before: by name
  candidates.erase(std::unique(candidates.begin() + static_cast<std::ptrdiff_t>(first_legacy), candidates.end()),
                   candidates.end());
  for (std::size_t i = 0; i < mapping_->entries().size(); ++i) {
    const yaml::MapEntry& entry = mapping_->entries()[i];
    if (consumed(i) || entry.merged) continue;
    const std::string_view match = closest_key(entry.key, candidates);
    std::string_view guess = match;
    if (std::string_view modern = modern_of(guess); !modern.empty()) guess = modern;
    if (match == entry.key && guess != match) {
      report_second_spelling(entry, guess);
    } else if (!guess.empty()) {
      // The rename is a fix-it only when the guess is the one candidate that close and no
      // spelling of it is in the mapping already; it is unsafe: the value is then read.
      std::vector<FixIt> fixes;
      if (unique_guess(entry.key, candidates, guess) && !mapping_->find(guess) && !has_spelling_of(guess))
        if (auto fix = edit_key(entry, std::string(guess), FixSafety::kUnsafe)) fixes.push_back(std::move(*fix));
      const bool physical = changes_model(guess) && entry.key != match;
      ctx_.report(physical ? "load-unknown-model-key" : "load-unknown-key", entry.key_location,
                  "unknown key \"" + std::string(entry.key) + "\" in " + what_ + "; did you mean \"" +
                      std::string(guess) + "\"?" +
                      (physical ? " Choreonoid ignores it, so " + std::string(guess) + " keeps its default" : ""),
                  (physical ? "" : "Choreonoid ignores it; ") + std::string("rename it to ") + std::string(guess),
                  std::move(fixes));
    } else {
      ctx_.report("load-info-key", entry.key_location,
                  "key \"" + std::string(entry.key) + "\" is not part of the " + what_ + " format; it is kept as info");
    }
  }
}

void MappingReader::report_second_spelling(const yaml::MapEntry& entry, std::string_view modern) {
  // take() consumed the first spelling of its list that is present, as Choreonoid's
  // Mapping::extract and Mapping::read try their key lists in order (src/Util/ValueTree.cpp):
  // the modern snake_case spelling wins over a camelCase one. The entry read is the consumed
  // one among the spellings of `modern`.
  const yaml::MapEntry* read = nullptr;
  for (std::size_t j = 0; j < mapping_->entries().size() && !read; ++j) {
    const yaml::MapEntry& other = mapping_->entries()[j];
    if (consumed(j) && (other.key == modern || modern_of(other.key) == modern)) read = &other;
  }
  if (!read) return;  // cannot be: this spelling was only left because another was taken
  // Removing the ignored spelling is unsafe: Mapping::read (shapes, devices, gear_ratio) goes
  // on to the next spelling when a value does not convert, so the one ignored here may be read
  // after all; `bodycheck --fix` leaves it to the user. A value that defines an anchor stays.
  std::vector<FixIt> fixes;
  if (const std::optional<EntryLines> lines = entry_lines(ctx_, mapping_, entry)) {
    const std::string_view text = ctx_.text.substr(lines->begin, lines->end - lines->begin);
    if (text.find('&') == std::string_view::npos) {
      FixIt fix;
      fix.file = entry.key_location.file;
      fix.begin = lines->begin;
      fix.end = lines->end;
      fix.line = entry.key_location.line;
      fix.column = 1;
      fix.original = std::string(text);
      fix.safety = FixSafety::kUnsafe;
      fixes.push_back(std::move(fix));
    }
  }
  const std::string where = read->key_location.file == entry.key_location.file
                                ? "line " + std::to_string(read->key_location.line)
                                : read->key_location.file.str() + ":" + std::to_string(read->key_location.line);
  ctx_.report("load-key-written-twice", entry.key_location,
              "key \"" + std::string(entry.key) + "\" is \"" + std::string(read->key) + "\" (" + where +
                  ") written a second time in this " + what_ + ", in another spelling; Choreonoid reads \"" +
                  std::string(read->key) + "\" and ignores this one",
              "remove one of them (this one is ignored)", std::move(fixes));
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
