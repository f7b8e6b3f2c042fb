#include <bodyfmt/diagnostic.h>

#include <algorithm>
#include <mutex>
#include <tuple>
#include <unordered_set>

namespace bodyfmt {

namespace {
const std::string kEmptyName;
}

FileName::FileName(const std::string& name) {
  if (name.empty()) return;
  // Never freed: a process names few files, and every location may point at them.
  static std::mutex mutex;
  static std::unordered_set<std::string>* names = new std::unordered_set<std::string>();
  const std::lock_guard<std::mutex> lock(mutex);
  name_ = &*names->insert(name).first;
}

const std::string& FileName::str() const { return name_ ? *name_ : kEmptyName; }

std::string_view severity_name(Severity severity) {
  switch (severity) {
    case Severity::kNote: return "note";
    case Severity::kWarning: return "warning";
    case Severity::kError: return "error";
    case Severity::kFatal: return "fatal error";
  }
  return "error";
}

std::string_view fix_safety_name(FixSafety safety) {
  switch (safety) {
    case FixSafety::kSafe: return "safe";
    case FixSafety::kUpgrade: return "upgrade";
    case FixSafety::kUnsafe: return "unsafe";
  }
  return "unsafe";
}

void CollectingSink::report(Diagnostic diagnostic) { diagnostics_.push_back(std::move(diagnostic)); }

int CollectingSink::count(Severity severity) const {
  return static_cast<int>(std::count_if(diagnostics_.begin(), diagnostics_.end(),
                                        [&](const Diagnostic& d) { return d.severity == severity; }));
}

bool CollectingSink::has(std::string_view rule_id) const {
  return std::any_of(diagnostics_.begin(), diagnostics_.end(),
                     [&](const Diagnostic& d) { return d.rule_id == rule_id; });
}

void LocatingSink::report(Diagnostic diagnostic) {
  if (!diagnostic.location.known()) diagnostic.location = fallback_;
  inner_.report(std::move(diagnostic));
}

static std::string format_location(const SourceLocation& location) {
  std::string text = location.file.empty() ? std::string("<input>") : location.file.str();
  if (location.line > 0) {
    text += ':' + std::to_string(location.line);
    if (location.column > 0) text += ':' + std::to_string(location.column);
  }
  return text;
}

std::string format_diagnostic(const Diagnostic& d) {
  std::string text = format_location(d.location) + ": " + std::string(severity_name(d.severity)) + ": " + d.message;
  if (!d.rule_id.empty()) text += " [" + d.rule_id + "]";
  if (d.via) text += "\n" + format_location(*d.via) + ": note: reached through this alias";
  if (!d.fix_hint.empty()) text += "\n" + format_location(d.location) + ": note: " + d.fix_hint;
  return text;
}

void sort_diagnostics(std::vector<Diagnostic>& diagnostics) {
  const auto before = [](const Diagnostic& a, const Diagnostic& b) {
    return std::tie(a.location.file, a.location.line, a.location.column, a.rule_id) <
           std::tie(b.location.file, b.location.line, b.location.column, b.rule_id);
  };
  if (std::is_sorted(diagnostics.begin(), diagnostics.end(), before)) return;  // the rules' order, often
  // Sorted as indices, then moved into place along the permutation's cycles: a stable sort of
  // the diagnostics themselves would allocate a second array of them.
  std::vector<std::size_t> order(diagnostics.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return before(diagnostics[a], diagnostics[b]); });
  for (std::size_t start = 0; start < order.size(); ++start) {
    if (order[start] == start) continue;
    Diagnostic held = std::move(diagnostics[start]);
    std::size_t k = start;
    while (order[k] != start) {  // position k receives the diagnostic at order[k]
      const std::size_t from = order[k];
      diagnostics[k] = std::move(diagnostics[from]);
      order[k] = k;
      k = from;
    }
    diagnostics[k] = std::move(held);
    order[k] = k;
  }
}

}  // namespace bodyfmt
