// Applies fix-its to one file's text, and writes the unified diff of the result.

#include <bodyfmt/fix.h>

#include "text/text_util.h"

#include <fmt/format.h>

#include <algorithm>
#include <tuple>

namespace bodyfmt {

std::optional<std::string> apply_fixes(std::string_view text, std::vector<FixIt> fixes, std::string& why) {
  std::sort(fixes.begin(), fixes.end(), [](const FixIt& a, const FixIt& b) {
    return std::tie(a.begin, a.end, a.replacement) < std::tie(b.begin, b.end, b.replacement);
  });
  fixes.erase(std::unique(fixes.begin(), fixes.end(),
                          [](const FixIt& a, const FixIt& b) {
                            return a.begin == b.begin && a.end == b.end && a.replacement == b.replacement;
                          }),
              fixes.end());
  std::string out;
  out.reserve(text.size());
  std::size_t at = 0;
  for (const FixIt& fix : fixes) {
    const std::string where = fmt::format("{}:{}:{}", fix.file.str(), fix.line, fix.column);
    if (fix.begin > fix.end || fix.end > text.size() || text.substr(fix.begin, fix.end - fix.begin) != fix.original) {
      why = where + ": the text to replace (\"" + fix.original + "\") is not there: the file changed since it was read";
      return std::nullopt;
    }
    if (fix.begin < at) {
      why = where + ": two different edits overlap here";
      return std::nullopt;
    }
    out.append(text.substr(at, fix.begin - at));
    out += fix.replacement;
    at = fix.end;
  }
  out.append(text.substr(at));
  return out;
}

namespace {

// Lines with their terminators, so that a missing final newline is a difference too.
std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    end = end == std::string_view::npos ? text.size() : end + 1;
    lines.push_back(text.substr(pos, end - pos));
    pos = end;
  }
  return lines;
}

enum class Op { kKeep, kRemove, kAdd };

// Myers' O((N+M)D) shortest edit script; fix-its change few lines, so D is small. Lines equal
// at both ends are matched first, which keeps the search to the changed middle.
std::vector<std::pair<Op, std::size_t>> edit_script(const std::vector<std::string_view>& a,
                                                    const std::vector<std::string_view>& b) {
  const long n = static_cast<long>(a.size()), m = static_cast<long>(b.size());
  const long max = n + m;
  std::vector<long> v(static_cast<std::size_t>(2 * max + 2), 0);
  std::vector<std::vector<long>> trace;
  const auto at = [&](long k) -> long& { return v[static_cast<std::size_t>(k + max + 1)]; };
  long d_found = -1;
  for (long d = 0; d <= max && d_found < 0; ++d) {
    trace.push_back(v);
    for (long k = -d; k <= d; k += 2) {
      long x = (k == -d || (k != d && at(k - 1) < at(k + 1))) ? at(k + 1) : at(k - 1) + 1;
      long y = x - k;
      while (x < n && y < m && a[static_cast<std::size_t>(x)] == b[static_cast<std::size_t>(y)]) ++x, ++y;
      at(k) = x;
      if (x >= n && y >= m) {
        d_found = d;
        break;
      }
    }
  }
  // Walk back through the saved frontiers.
  std::vector<std::pair<Op, std::size_t>> script;
  long x = n, y = m;
  for (long d = d_found; d > 0; --d) {
    v = trace[static_cast<std::size_t>(d)];
    const long k = x - y;
    const long prev_k = (k == -d || (k != d && at(k - 1) < at(k + 1))) ? k + 1 : k - 1;
    const long prev_x = at(prev_k), prev_y = prev_x - prev_k;
    while (x > prev_x && y > prev_y) script.emplace_back(Op::kKeep, static_cast<std::size_t>(--x)), --y;
    if (x == prev_x)
      script.emplace_back(Op::kAdd, static_cast<std::size_t>(--y));
    else
      script.emplace_back(Op::kRemove, static_cast<std::size_t>(--x));
  }
  while (x > 0) script.emplace_back(Op::kKeep, static_cast<std::size_t>(--x)), --y;
  std::reverse(script.begin(), script.end());
  return script;
}

std::string diff_line(char sign, std::string_view line) {
  std::string out(1, sign);
  out += line;
  if (out.back() != '\n') out += "\n\\ No newline at end of file\n";
  return out;
}

std::string range_text(std::size_t start, std::size_t count) {
  // diff -u: an empty range is written at the line before it.
  if (count == 0) return fmt::format("{},0", start);
  return count == 1 ? fmt::format("{}", start + 1) : fmt::format("{},{}", start + 1, count);
}

}  // namespace

std::string unified_diff(std::string_view before, std::string_view after, const std::string& name) {
  if (before == after) return {};
  const std::vector<std::string_view> a = lines_of(before), b = lines_of(after);
  // Common head and tail lines are kept out of the search.
  std::size_t head = 0;
  while (head < a.size() && head < b.size() && a[head] == b[head]) ++head;
  std::size_t tail = 0;
  while (tail < a.size() - head && tail < b.size() - head && a[a.size() - 1 - tail] == b[b.size() - 1 - tail]) ++tail;
  const std::vector<std::string_view> a_mid(a.begin() + static_cast<long>(head), a.end() - static_cast<long>(tail));
  const std::vector<std::string_view> b_mid(b.begin() + static_cast<long>(head), b.end() - static_cast<long>(tail));
  struct Step {
    Op op;
    std::size_t ai, bi;  // line indices in a and b before this step
  };
  std::vector<Step> steps;
  std::size_t ai = 0, bi = 0;
  const auto push = [&](Op op) {
    steps.push_back(Step{op, ai, bi});
    if (op != Op::kAdd) ++ai;
    if (op != Op::kRemove) ++bi;
  };
  for (std::size_t i = 0; i < head; ++i) push(Op::kKeep);
  if (a_mid.size() == b_mid.size()) {
    // Fix-its edit within lines, so line i stays line i: pair them up (no search, no memory
    // beyond the lines), each run of changed lines as its removals then its additions.
    for (std::size_t j = 0; j < a_mid.size();) {
      if (a_mid[j] == b_mid[j]) {
        push(Op::kKeep);
        ++j;
        continue;
      }
      std::size_t run = j;
      while (run < a_mid.size() && a_mid[run] != b_mid[run]) ++run;
      for (std::size_t r = j; r < run; ++r) push(Op::kRemove);
      for (std::size_t r = j; r < run; ++r) push(Op::kAdd);
      j = run;
    }
  } else {
    for (const auto& step : edit_script(a_mid, b_mid)) push(step.first);
  }
  for (std::size_t i = 0; i < tail; ++i) push(Op::kKeep);

  constexpr std::size_t kContext = 3;
  // An absolute path is written as git writes one (`a/tmp/x.body`, not `a//tmp/x.body`), so that
  // `patch -p1` run from the root applies it.
  const std::string shown = name.substr(std::min(name.find_first_not_of('/'), name.size()));
  std::string out = "--- a/" + shown + "\n+++ b/" + shown + "\n";
  std::size_t i = 0;
  while (i < steps.size()) {
    if (steps[i].op == Op::kKeep) {
      ++i;
      continue;
    }
    // A hunk: from kContext lines before this change to kContext after the last change that
    // is at most 2 * kContext kept lines from the next.
    const std::size_t start = i >= kContext ? i - kContext : 0;
    std::size_t end = i;
    std::size_t kept = 0;
    for (std::size_t j = i; j < steps.size(); ++j) {
      if (steps[j].op == Op::kKeep) {
        if (++kept > 2 * kContext) break;
      } else {
        kept = 0;
        end = j;
      }
    }
    const std::size_t stop = std::min(steps.size(), end + 1 + kContext);
    std::size_t a_count = 0, b_count = 0;
    std::string body;
    for (std::size_t j = start; j < stop; ++j) {
      const Step& s = steps[j];
      if (s.op == Op::kKeep) {
        body += diff_line(' ', a[s.ai]);
        ++a_count, ++b_count;
      } else if (s.op == Op::kRemove) {
        body += diff_line('-', a[s.ai]);
        ++a_count;
      } else {
        body += diff_line('+', b[s.bi]);
        ++b_count;
      }
    }
    out += "@@ -" + range_text(steps[start].ai, a_count) + " +" + range_text(steps[start].bi, b_count) + " @@\n";
    out += body;
    i = stop;
  }
  return out;
}

}  // namespace bodyfmt
