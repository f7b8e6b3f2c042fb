#include "report_lines.h"

#include <fmt/format.h>

#include <regex>
#include <string_view>

namespace bodyfmt::tools {

namespace {

/// The byte at which the code point after the first `n` starts (the size when there are fewer).
std::size_t byte_of_column(const std::string& text, std::size_t n) {
  std::size_t seen = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) continue;  // inside a UTF-8 sequence
    if (seen++ == n) return i;
  }
  return text.size();
}

}  // namespace

std::string number(double value) { return fmt::format("{:.6g}", value); }

std::string wrap(const std::string& text, std::size_t indent) {
  std::string out, rest = text;
  const std::string pad(indent, ' ');
  // Spaces inside a line are kept as written ("PASS  name", "measured 1  expected 2").
  while (byte_of_column(rest, kReportColumns) < rest.size()) {
    const std::size_t limit = byte_of_column(rest, kReportColumns);
    const std::size_t lead = rest.find_first_not_of(' ');
    std::size_t cut = rest.rfind(' ', limit);
    if (cut == std::string::npos || cut <= lead) cut = rest.find(' ', limit);  // one word longer than a line
    if (cut == std::string::npos) break;
    std::size_t end = cut;
    while (end > 0 && rest[end - 1] == ' ') --end;
    const std::size_t next = rest.find_first_not_of(' ', cut);
    if (next == std::string::npos) {
      rest.erase(end);
      break;
    }
    out += rest.substr(0, end) + '\n';
    rest = pad + rest.substr(next);
  }
  return out + rest + '\n';
}

std::pair<std::string, std::string> distinct_numbers(double value, double other) {
  int digits = 6;
  auto show = [&](double v) { return fmt::format("{:.{}g}", v, digits); };
  // Up to 10: a difference in the 11th digit is rounding (0.4999999999999998 against 0.5), far
  // below any tolerance a check states.
  while (digits < 10 && value != other && show(value) == show(other)) ++digits;
  return {show(value), show(other)};
}

namespace {

/// "G3 free fall: ..." -> "free fall: ... [G3]": the spec's code is for cross-reference only.
std::string code_at_end(const std::string& name) {
  static const std::regex code(R"(^(G\d+) (.*)$)");
  std::smatch m;
  if (std::regex_match(name, m, code)) return m[2].str() + " [" + m[1].str() + "]";
  return name;
}

}  // namespace

std::string check_lines(const dynamics::CheckResult& r) {
  const std::string verdict = r.skipped ? "SKIP" : r.passed ? "PASS" : "FAIL";
  const std::string name = code_at_end(r.name);
  if (r.skipped || (!r.note.empty() && r.tolerance.empty()))
    return wrap(fmt::format("{}  {}: {}", verdict, name, r.note), 6);
  const auto [measured, expected] = distinct_numbers(r.measured, r.expected);
  const std::string unit = r.unit.empty() ? "" : " " + r.unit;
  std::string out = wrap(verdict + "  " + name, 6);
  out += wrap(
      fmt::format("      measured {}{}  expected {}{}  tolerance {}", measured, unit, expected, unit, r.tolerance), 8);
  if (!r.note.empty()) out += wrap("      " + r.note, 6);
  return out;
}

std::string nothing_simulated(const std::string& tool, const std::string& why,
                              const std::vector<Diagnostic>& diagnostics) {
  std::string reason = why;
  for (const std::string_view said : {" (see above)", "; nothing was simulated", "nothing was simulated"}) {
    const std::size_t at = reason.find(said);
    if (at != std::string::npos) reason.erase(at, said.size());
  }
  std::string out = wrap(tool + ": error: nothing was simulated" + (reason.empty() ? "" : ": " + reason), 2);
  for (const Diagnostic& d : diagnostics) {
    if (d.severity < Severity::kError) continue;
    const SourceLocation& l = d.location;
    const std::string where = l.line > 0 ? fmt::format("{}:{}:{}", l.file.str(), l.line, l.column) : l.file.str();
    out += wrap(fmt::format("  stopped by {}: {} [{}]", where, d.message, d.rule_id), 4);
    if (!d.fix_hint.empty()) out += wrap("  to simulate it: " + d.fix_hint, 4);
    break;
  }
  return out;
}

}  // namespace bodyfmt::tools
