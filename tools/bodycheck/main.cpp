// bodycheck: checks .body files and reports located diagnostics as text, JSON or SARIF.
// Exit codes (tools/common/front.h): 0 nothing at or above the fail level, 1 findings,
// 2 usage, I/O or fatal error.

#include "compact_findings.h"
#include "fix_run.h"
#include "front.h"
#include "model_check.h"
#include "output_guard.h"
#include "text_view.h"

#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include <cstdio>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <thread>

#ifndef BODYCHECK_INFORMATION_URI
#define BODYCHECK_INFORMATION_URI ""
#endif

namespace fs = std::filesystem;
using namespace bodyfmt;

namespace {

struct Job {
  tools::ModelInput input;
  tools::Front::FilePolicy policy;
};

struct JobResult {
  std::vector<Diagnostic> diagnostics;
  std::vector<InputFile> inputs;  ///< the files the model was read from, when the report goes to a file
  bool loaded = false;
  int suppressed = 0;
  int disabled = 0;
};

struct Settings {
  std::string format = "text";
  std::string output;
  bool stats = false;
  bool list_rules = false;
  std::string explain;
  int jobs = 0;
  bool fix = false;
  std::string fix_class;  ///< "safe" (--fix) or "geometry" (--fix=geometry)
  bool git_models = false;
  std::string min_severity = "note";
  tools::FixSettings fixing;
};

/// The .body files in the git index of the current directory's repository (as paths from the
/// current directory), for a pre-commit hook: with every model checked, a mesh or an included
/// file that changed or was deleted fails the model that uses it. False if git fails.
bool git_models(std::vector<std::string>& files) {
  FILE* pipe = ::popen("git ls-files -z --cached -- '*.body' 2>/dev/null", "r");
  if (!pipe) return false;
  std::string out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  if (::pclose(pipe) != 0) return false;
  for (std::size_t begin = 0, end; begin < out.size(); begin = end + 1) {
    end = out.find('\0', begin);
    if (end == std::string::npos) end = out.size();
    const std::string path = out.substr(begin, end - begin);
    std::error_code ec;
    if (!path.empty() && fs::is_regular_file(path, ec)) files.push_back(path);
  }
  return true;
}

JobResult check_file(tools::Front& front, const Job& job, bool to_file) {
  tools::ModelCheck checked =
      tools::check_model_input(front.load_options(), job.input, job.policy.options, {to_file, false});
  JobResult result;
  result.diagnostics = std::move(checked.diagnostics);
  result.inputs = std::move(checked.inputs);
  result.loaded = checked.loaded;
  result.suppressed = checked.suppressed;
  result.disabled = checked.disabled;
  return result;
}

void print_rules(std::ostream& out) {
  std::size_t width = 0;
  for (const auto& rule : all_rules()) width = std::max(width, rule.id.size());
  for (const auto& rule : all_rules())
    out << fmt::format("{:<{}}  {:<11}  {}\n", rule.id, width, severity_name(rule.default_severity), rule.summary);
}

/// `--explain RULE`: the rule's row of the table (what docs/rules.md shows) in words.
void explain_rule(std::ostream& out, const RuleInfo& rule) {
  out << fmt::format("{}: {} by default\n", rule.id, severity_name(rule.default_severity));
  out << fmt::format("  what:      {}\n", rule.summary);
  out << fmt::format("  why:       {}\n", rule.rationale);
  if (!rule.tolerance.empty()) out << fmt::format("  threshold: {}\n", rule.tolerance);
  if (!rule.fix.empty()) out << fmt::format("  fix-it:    {}\n", rule.fix);
  out << fmt::format(
      "  settings:  --disable {0}, --severity {0}=note|warning|error (or `disable:` and `severity:` in "
      ".bodycheck.yaml), `# bodycheck: disable={0}` on a line\n",
      rule.id);
}

/// The files to check: `files` (from --git-models), each named file, and every *.body below each
/// named directory, in a stable order, each once. Missing paths are reported and fail the run.
std::vector<std::string> expand_inputs(const tools::Front& front, std::vector<std::string> files, bool& fatal) {
  for (const std::string& input : front.inputs()) {
    std::error_code ec;
    if (input == "-") {
      files.push_back(input);
    } else if (fs::is_directory(input, ec)) {
      std::vector<std::string> found;
      const std::size_t before = files.size();
      for (fs::recursive_directory_iterator it(input, fs::directory_options::skip_permission_denied, ec), end;
           !ec && it != end; it.increment(ec)) {
        if (it->path().extension() == ".body" && it->is_regular_file(ec))
          found.push_back(it->path().lexically_normal().string());
      }
      if (ec) {
        std::cerr << input << ": error: cannot read the directory: " << ec.message() << '\n';
        fatal = true;
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
      if (files.size() == before && !ec) {
        // A mistyped folder must not pass a CI job with "0 files checked".
        std::cerr << input << ": error: no model files found (no *.body below this folder)\n";
        fatal = true;
      }
    } else if (fs::exists(input, ec)) {
      files.push_back(fs::path(input).lexically_normal().string());
    } else {
      // Missing, or a symbolic link loop: the bounded reader's words, as every tool prints them.
      std::string why;
      readable_regular_file(input, front.load_options().max_file_bytes, why);
      std::cerr << input << ": error: " << why << '\n';
      fatal = true;
    }
  }
  // Each file once, compared by its canonical path: `a.body`, `./a.body` and `x/../a.body` are
  // one file (a file reached twice would report its findings twice).
  std::sort(files.begin(), files.end());
  std::set<std::string> seen;
  std::vector<std::string> unique;
  for (const std::string& file : files) {
    std::error_code ec;
    const fs::path canonical = file == "-" ? fs::path(file) : fs::weakly_canonical(file, ec);
    if (seen.insert(ec ? file : canonical.string()).second) unique.push_back(file);
  }
  return unique;
}

/// One job per file, with its policy (command line over its .bodycheck.yaml). A file whose
/// input or config cannot be read is left out and makes the run fail.
std::vector<Job> make_jobs(tools::Front& front, const std::vector<std::string>& files, bool& fatal) {
  std::vector<Job> jobs;
  for (const std::string& file : files) {
    auto policy = front.policy_for(file);
    if (!policy) {
      fatal = true;  // a malformed config: its files are not checked
      continue;
    }
    CollectingSink open_sink;
    auto input = front.open_input(file, open_sink);
    if (!input) {
      front.print(std::move(open_sink.diagnostics()));
      fatal = true;
      continue;
    }
    jobs.push_back(Job{std::move(*input), std::move(*policy)});
  }
  return jobs;
}

/// Checks the jobs on a few threads; each file's diagnostics are kept apart, in job order.
std::vector<JobResult> run_jobs(tools::Front& front, const std::vector<Job>& jobs, int requested_threads,
                                bool to_file) {
  std::vector<JobResult> results(jobs.size());
  unsigned threads = requested_threads > 0 ? static_cast<unsigned>(requested_threads)
                                           : std::clamp(std::thread::hardware_concurrency(), 2u, 4u);
  threads = std::min<unsigned>(threads, static_cast<unsigned>(std::max<std::size_t>(jobs.size(), 1)));
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < jobs.size();) results[i] = check_file(front, jobs[i], to_file);
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  return results;
}

/// One spelling per file: a file reached under several paths (`a/../b/x.body` on the command
/// line, `b/x.body` as another model's SubBody) is shown under the first spelling met, so its
/// findings are reported once.
class FileSpellings {
 public:
  FileName spelling(FileName file) {
    if (file.empty()) return file;
    auto known = by_spelling_.find(file);
    if (known != by_spelling_.end()) return known->second;
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(file.str(), ec);
    const std::string key = ec ? file.str() : canonical.string();
    const FileName shown = by_canonical_.emplace(key, file).first->second;
    by_spelling_.emplace(file, shown);
    return shown;
  }

 private:
  std::map<std::string, FileName> by_canonical_;
  std::map<FileName, FileName> by_spelling_;
};

/// Merges the results into one report, deciding the exit code on the way.
Report make_report(const std::vector<Job>& jobs, std::vector<JobResult>& results, bool quiet, bool& fatal,
                   bool& findings) {
  Report report;
  FileSpellings spellings;
  std::size_t total = 0;
  for (const JobResult& r : results) total += r.diagnostics.size();
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    JobResult& r = results[i];
    report.files.push_back(jobs[i].input.name);
    report.suppressed += r.suppressed;
    report.disabled += r.disabled;
    if (!r.loaded) fatal = true;
    switch (tools::exit_code(r.diagnostics, jobs[i].policy.exit, false)) {
      case tools::kExitFatal: fatal = true; break;
      case tools::kExitFindings: findings = true; break;
      default: break;
    }
    if (quiet)
      r.diagnostics.erase(std::remove_if(r.diagnostics.begin(), r.diagnostics.end(),
                                         [](const Diagnostic& d) { return d.severity == Severity::kNote; }),
                          r.diagnostics.end());
    for (Diagnostic& d : r.diagnostics) {
      d.location.file = spellings.spelling(d.location.file);
      if (d.via) d.via->file = spellings.spelling(d.via->file);
    }
    // The first file's findings are taken over whole, so that a run of one large model never
    // holds its findings in two arrays at once; the others are appended, and their arrays freed.
    if (report.diagnostics.empty()) {
      report.diagnostics = std::move(r.diagnostics);
    } else {
      report.diagnostics.reserve(total);
      std::move(r.diagnostics.begin(), r.diagnostics.end(), std::back_inserter(report.diagnostics));
    }
    r.diagnostics = std::vector<Diagnostic>();
  }
  tools::sort_unique_findings(report.diagnostics);
  return report;
}

/// Writes the report to stdout or to --output; the text format a block at a time (a report of
/// a million findings is never held as one string).
bool write_report(tools::Front& front, const Report& report, const Settings& settings,
                  const std::vector<InputFile>& inputs) {
  // Checked before the file is opened, which would empty it.
  const std::string clash = tools::input_clash(settings.output, inputs);
  if (!clash.empty()) {
    front.print_error(settings.output + ": cannot write the report: " + clash + "; nothing was written");
    return false;
  }
  ToolInfo tool;
  tool.version = BODYFMT_VERSION;
  tool.information_uri = BODYCHECK_INFORMATION_URI;
  const auto cannot_write = [&] {
    front.print_error(settings.output + ": cannot write the report: " +
                      (errno != 0 ? std::string(std::strerror(errno)) : std::string("a write error")));
    return false;
  };
  errno = 0;
  std::ofstream file;
  if (!settings.output.empty()) {
    file.open(settings.output, std::ios::binary);
    if (!file.is_open()) return cannot_write();
  }
  std::ostream& out = settings.output.empty() ? std::cout : file;
  if (settings.format == "json") {
    out << format_json_report(report, tool);
  } else if (settings.format == "sarif") {
    out << format_sarif_report(report, tool);
  } else {
    const bool terminal = settings.output.empty() && ::isatty(STDOUT_FILENO) != 0;
    tools::TextView view;
    view.text = front.text_options(terminal);
    view.min_severity = *tools::parse_rule_severity(settings.min_severity);
    view.summary = !front.quiet();
    if (settings.git_models) view.paths.push_back("--git-models");
    view.paths.insert(view.paths.end(), front.inputs().begin(), front.inputs().end());
    tools::write_text_view(out, report, front.sources(), view);
  }
  if (settings.stats) {
    std::string lines;
    for (const auto& [rule, n] : report.counts_by_rule()) lines += fmt::format("{:>6}  {}\n", n, rule);
    if (settings.format == "text")
      out << lines;
    else
      std::cerr << lines;
  }
  if (settings.output.empty()) {
    out << std::flush;
    return true;
  }
  file.close();
  return file ? true : cannot_write();
}

}  // namespace

int main(int argc, char** argv) {
  tools::Front front("bodycheck", "Check Choreonoid .body models: located diagnostics as text, JSON or SARIF",
                     {true, false});
  Settings settings;
  CLI::App& app = front.app();
  app.add_option("--format", settings.format, "output format")->check(CLI::IsMember({"text", "json", "sarif"}));
  app.add_option("--min-severity", settings.min_severity,
                 "text format: print only findings at or above this severity (note, warning or error; every "
                 "finding is still counted, and JSON and SARIF keep them all)")
      ->check(CLI::IsMember({"note", "warning", "error"}));
  app.add_flag("--stats", settings.stats, "print the number of findings per rule");
  app.add_flag("--list-rules", settings.list_rules, "list every rule with its default severity and exit");
  app.add_option("--explain", settings.explain, "print the documentation of a rule (its row of docs/rules.md) and exit")
      ->check(
          [](const std::string& id) {
            return find_rule(id)                    ? std::string()
                   : check_rule_pattern(id).empty() ? "not a rule id: " + id
                                                    : check_rule_pattern(id);
          },
          "RULE");
  app.add_option("-o,--output", settings.output, "write the report to this file instead of stdout");
  app.add_option("-j,--jobs", settings.jobs, "worker threads (default: 2 to 4, by the cores available)")
      ->check(CLI::Range(1, 64));
  app.add_flag("--git-models", settings.git_models,
               "also check every .body file in the git index (the pre-commit hook: a changed or deleted mesh or "
               "included file fails the models that use it)");
  const std::string fixing = "Fixing";
  CLI::Option* fix_option =
      app.add_flag("--fix{safe}", settings.fix_class,
                   "apply the safe fix-its in place (docs/rules.md), after re-loading the result to prove the model "
                   "is unchanged; then report what remains (KIND safe, the default). --fix=geometry instead replaces "
                   "the centre of mass and inertia of the links an inertia rule flags with those of their shapes at "
                   "their written mass (RigidBody elements too, each from the shapes below it)")
          ->check(CLI::IsMember({"safe", "geometry"}))
          ->option_text("[=KIND]")
          ->group(fixing);
  app.add_flag("--all-links", settings.fixing.all_links,
               "with --fix=geometry: recompute every link's mass data from its shapes, not only the flagged links'")
      ->needs(fix_option)
      ->group(fixing);
  app.add_flag("--dry-run", settings.fixing.dry_run, "with --fix: print a unified diff instead of writing")
      ->needs(fix_option)
      ->group(fixing);
  app.add_flag("--upgrade", settings.fixing.upgrade,
               "with --fix: also rewrite format 1.0 files as 2.0 (radian values converted to degrees; "
               "docs/tools/bodycheck.md, \"Fixing\")")
      ->needs(fix_option)
      ->group(fixing);
  app.add_flag("--fix-includes", settings.fixing.includes,
               "with --fix: also edit SubBody and YAML resource files that are not named on the command line")
      ->needs(fix_option)
      ->group(fixing);
  if (auto code = front.parse(argc, argv)) return *code;
  settings.fix = !settings.fix_class.empty();
  settings.fixing.geometry = settings.fix_class == "geometry";
  if (settings.fixing.all_links && !settings.fixing.geometry) {
    front.print_error("--all-links is a choice of --fix=geometry: which links to recompute from their shapes");
    return tools::kExitFatal;
  }
  if (settings.fixing.geometry && settings.fixing.upgrade) {
    front.print_error("--fix=geometry and --upgrade are separate runs: upgrade first, then fix the geometry");
    return tools::kExitFatal;
  }
  if (settings.list_rules) {
    print_rules(std::cout);
    return tools::kExitClean;
  }
  if (!settings.explain.empty()) {
    explain_rule(std::cout, *find_rule(settings.explain));
    return tools::kExitClean;
  }
  std::vector<std::string> tracked;
  if (settings.git_models) {
    if (!git_models(tracked)) {
      front.print_error("--git-models: `git ls-files` failed; run it inside a git work tree");
      return tools::kExitFatal;
    }
    if (tracked.empty() && front.inputs().empty()) {
      if (!front.quiet()) std::cerr << "bodycheck: no .body files in the git index; nothing to check\n";
      return tools::kExitClean;
    }
  } else if (front.inputs().empty()) {
    front.print_error("no input files (bodycheck --help)");
    return tools::kExitFatal;
  }

  bool fatal = false;
  bool findings = false;
  const std::vector<std::string> files = expand_inputs(front, tracked, fatal);
  if (settings.fix) {
    const tools::FixSummary summary = tools::run_fixes(front, files, settings.fixing);
    fatal = fatal || summary.failed;
    if (settings.fixing.dry_run) {
      std::cout << summary.diff << std::flush;
      if (!front.quiet())
        std::cerr << fmt::format("bodycheck: {} edit{} in {} file{} would be made\n", summary.edits,
                                 summary.edits == 1 ? "" : "s", summary.files_changed,
                                 summary.files_changed == 1 ? "" : "s");
      if (fatal) return tools::kExitFatal;
      return summary.diff.empty() ? tools::kExitClean : tools::kExitFindings;
    }
  }
  const std::vector<Job> jobs = make_jobs(front, files, fatal);
  const bool to_file = !settings.output.empty();
  std::vector<JobResult> results = run_jobs(front, jobs, settings.jobs, to_file);
  std::vector<InputFile> inputs;
  if (to_file)
    for (const std::string& file : files) inputs.push_back({file, "the model"});
  for (JobResult& r : results) std::move(r.inputs.begin(), r.inputs.end(), std::back_inserter(inputs));
  const Report report = make_report(jobs, results, front.quiet(), fatal, findings);
  if (!write_report(front, report, settings, inputs)) return tools::kExitFatal;
  if (fatal) return tools::kExitFatal;
  return findings ? tools::kExitFindings : tools::kExitClean;
}
