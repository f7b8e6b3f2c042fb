#include <bodyfmt/diagnostic.h>

#include "text/text_util.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <unordered_map>

namespace bodyfmt {

namespace {
const std::string kEmptyName;
}

namespace {

// The process's file names, numbered from 1 in the order they are first met. Never freed: a
// process names few files, and every location may refer to them. Names are read without a
// lock (locations are printed from several threads): a name's slot is written before its
// number is handed out, and slots never move (fixed pages of a fixed page table).
constexpr std::size_t kPageBits = 10;
constexpr std::size_t kPageSize = std::size_t{1} << kPageBits;
constexpr std::size_t kPages = std::size_t{1} << 12;  // ~4 million names
using NamePage = std::array<std::atomic<const std::string*>, kPageSize>;

struct NameTable {
  std::mutex mutex;
  std::unordered_map<std::string_view, std::uint32_t> ids;  // views of the names in the pages
  std::array<std::atomic<NamePage*>, kPages> pages{};
  std::uint32_t next = 1;
};

NameTable& table() {
  static NameTable* names = new NameTable();
  return *names;
}

}  // namespace

FileName::FileName(const std::string& name) {
  if (name.empty()) return;
  NameTable& t = table();
  const std::lock_guard<std::mutex> lock(t.mutex);
  auto known = t.ids.find(name);
  if (known != t.ids.end()) {
    id_ = known->second;
    return;
  }
  const std::uint32_t id = t.next;
  const std::size_t page = id >> kPageBits;
  if (page >= kPages) throw std::length_error("more than 4 million distinct file names");
  if (!t.pages[page].load(std::memory_order_relaxed)) t.pages[page].store(new NamePage(), std::memory_order_release);
  const std::string* stored = new std::string(name);
  (*t.pages[page].load(std::memory_order_relaxed))[id & (kPageSize - 1)].store(stored, std::memory_order_release);
  t.ids.emplace(*stored, id);
  ++t.next;
  id_ = id;
}

const std::string& FileName::str() const {
  if (id_ == 0) return kEmptyName;
  const NamePage* page = table().pages[id_ >> kPageBits].load(std::memory_order_acquire);
  return *(*page)[id_ & (kPageSize - 1)].load(std::memory_order_acquire);
}

SourceLocation first_known(std::initializer_list<SourceLocation> locations) {
  const SourceLocation* last = nullptr;
  for (const SourceLocation& l : locations) {
    if (l.known()) return l;
    last = &l;
  }
  return last ? *last : SourceLocation{};
}

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
  std::string text = format_location(d.location) + ": " + std::string(severity_name(d.severity)) + ": ";
  text::append_one_line(text, d.message);  // a name's line break would split the diagnostic
  if (!d.rule_id.empty()) text += " [" + d.rule_id + "]";
  if (d.via) text += "\n" + format_location(*d.via) + ": note: reached through this alias";
  if (!d.fix_hint.empty()) {
    text += "\n" + format_location(d.location) + ": note: ";
    text::append_one_line(text, d.fix_hint);
  }
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
