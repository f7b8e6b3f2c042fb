#include "report.h"

#include <iostream>

namespace bodyfmt::bodyview {

std::string findings_summary(const std::vector<Diagnostic>& findings, bool notes, const std::string& where) {
  int counts[4] = {0, 0, 0, 0};  // by Severity
  for (const Diagnostic& d : findings)
    if (notes || d.severity != Severity::kNote) ++counts[static_cast<int>(d.severity)];
  const int total = counts[0] + counts[1] + counts[2] + counts[3];
  if (total == 0) return {};
  std::string parts;
  for (Severity s : {Severity::kFatal, Severity::kError, Severity::kWarning, Severity::kNote}) {
    const int n = counts[static_cast<int>(s)];
    if (n == 0) continue;
    if (!parts.empty()) parts += ", ";
    parts += std::to_string(n) + " " + std::string(severity_name(s)) + (n == 1 ? "" : "s");
  }
  return std::to_string(total) + (total == 1 ? " finding (" : " findings (") + parts + ") on the page " + where +
         "; --verbose prints them";
}

void report_page_findings(tools::Front& front, const std::vector<Diagnostic>& findings, bool verbose,
                          const std::string& where) {
  if (verbose) {
    front.print(findings);
    return;
  }
  const std::string line = findings_summary(findings, !front.quiet(), where);
  if (!line.empty()) std::cerr << "bodyview: " << line << std::endl;
}

}  // namespace bodyfmt::bodyview
