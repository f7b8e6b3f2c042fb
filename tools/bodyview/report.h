#pragma once
// What bodyview prints of the findings its page lists: one summary line, since the page shows
// every finding with its source line; --verbose prints them all, as the other tools do.

#include "front.h"

#include <string>
#include <vector>

namespace bodyfmt::bodyview {

/// "N findings (A errors, B warnings, C notes) on the page WHERE; --verbose prints them", or
/// empty when there is nothing to count. Notes are left out when `notes` is false (-q).
std::string findings_summary(const std::vector<Diagnostic>& findings, bool notes, const std::string& where);

/// Prints the findings a page lists: every one when `verbose`, else the summary line (to stderr,
/// after "bodyview: "). A finding the page cannot show (no page) is the caller's to print.
void report_page_findings(tools::Front& front, const std::vector<Diagnostic>& findings, bool verbose,
                          const std::string& where);

}  // namespace bodyfmt::bodyview
