#include "export_summary.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace bodyfmt::tools {

namespace fs = std::filesystem;

namespace {

/// "12 files in out/meshes/a" per folder of generated files, or empty when there are none.
std::string generated_files(const converters::OutputSet& out) {
  std::map<std::string, int> per_folder;
  const std::string main = out.to_stdout() ? std::string("-") : out.main_path().filename().string();
  for (const auto& [relative, contents] : out.files()) {
    const fs::path path(relative);
    if (relative == main || path.filename() == converters::OutputSet::kRecordName) continue;
    const fs::path folder = out.to_stdout() ? path.parent_path() : out.directory() / path.parent_path();
    per_folder[folder.lexically_normal().generic_string()] += 1;
  }
  std::string text;
  for (const auto& [folder, count] : per_folder)
    text += fmt::format("{}{} file{} in {}", text.empty() ? "" : ", ", count, count == 1 ? "" : "s",
                        folder.empty() || folder == "." ? std::string("./") : folder + "/");
  return text;
}

}  // namespace

std::string export_summary(const converters::OutputSet& out, const std::vector<Diagnostic>& diagnostics,
                           const ExitPolicy& policy) {
  std::string text = "wrote " + (out.to_stdout() ? std::string("standard output") : out.main_path().string());
  const std::string generated = generated_files(out);
  if (!generated.empty()) text += " and " + generated;

  // Kinds in order of first appearance, so the line follows the report above it.
  std::vector<std::pair<std::string, int>> losses;
  std::map<std::string, int> other_export_findings;
  for (const Diagnostic& d : diagnostics) {
    if (d.rule_id == "export-loss") {
      auto it = std::find_if(losses.begin(), losses.end(), [&](const auto& kind) { return kind.first == d.category; });
      if (it == losses.end())
        losses.emplace_back(d.category, 1);
      else
        it->second += 1;
    } else if (d.rule_id.rfind("export-", 0) == 0 && d.severity == Severity::kWarning) {
      other_export_findings[d.rule_id] += 1;
    }
  }
  if (losses.empty()) {
    text += "; nothing lost";
  } else {
    int total = 0;
    std::string counts, unaccepted;
    for (const auto& [kind, count] : losses) {
      total += count;
      counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", count, kind);
      const bool accepted =
          std::find(policy.allowed_losses.begin(), policy.allowed_losses.end(), kind) != policy.allowed_losses.end();
      if (!accepted) unaccepted += (unaccepted.empty() ? "" : ",") + kind;
    }
    text += fmt::format("; {} loss{} ({})", total, total == 1 ? "" : "es", counts);
    if (!unaccepted.empty()) text += "; --allow-loss " + unaccepted + " accepts them";
  }
  for (const auto& [rule, count] : other_export_findings) text += fmt::format("; {} {}", count, rule);
  return text;
}

}  // namespace bodyfmt::tools
