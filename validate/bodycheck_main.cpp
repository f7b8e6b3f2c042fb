// bodycheck: checks .body files and reports located diagnostics as text, JSON or SARIF.
// Exit codes: 0 nothing at or above the fail level, 1 findings, 2 usage, I/O or fatal error.

#include <bodyfmt/derived.h>
#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/load.h>
#include <bodyfmt/report.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <thread>

#ifndef BODYFMT_VERSION
#define BODYFMT_VERSION "0"
#endif
#ifndef BODYCHECK_INFORMATION_URI
#define BODYCHECK_INFORMATION_URI ""
#endif

namespace fs = std::filesystem;
using bodyfmt::Diagnostic;
using bodyfmt::Severity;

namespace {

struct Job {
  std::string file;
  bodyfmt::PolicyOptions policy;
};

struct JobResult {
  std::vector<Diagnostic> diagnostics;
  bool loaded = false;
  int suppressed = 0;
  int disabled = 0;
};

JobResult check_file(const Job& job, const bodyfmt::LoadOptions& load_options) {
  JobResult result;
  bodyfmt::CollectingSink collected;
  bodyfmt::DiagnosticPolicy policy(collected, job.policy);
  try {
    auto model = bodyfmt::load_body(job.file, load_options, policy);
    result.loaded = model.has_value();
    if (model) {
      bodyfmt::Derived derived = bodyfmt::compute_derived(*model, policy);
      bodyfmt::validate::check_model(*model, derived, {}, policy);
    }
  } catch (const std::exception& e) {
    Diagnostic d;
    d.severity = Severity::kFatal;
    d.rule_id = "internal-error";
    d.message = std::string("unexpected failure: ") + e.what();
    d.location.file = job.file;
    policy.report(std::move(d));
    result.loaded = false;
  }
  result.diagnostics = std::move(collected.diagnostics());
  result.suppressed = policy.suppressed_count();
  result.disabled = policy.disabled_count();
  return result;
}

/// Rule ids from the table switched off by the layered settings: command line over config,
/// and within each, enable over disable.
std::vector<std::string> disabled_rules(const std::vector<std::string>& cli_disable,
                                        const std::vector<std::string>& cli_enable,
                                        const bodyfmt::CheckConfig* config) {
  auto any = [](const std::vector<std::string>& patterns, std::string_view id) {
    return std::any_of(patterns.begin(), patterns.end(),
                       [&](const std::string& p) { return bodyfmt::rule_pattern_matches(p, id); });
  };
  std::vector<std::string> off;
  for (const bodyfmt::RuleInfo& rule : bodyfmt::all_rules()) {
    bool enabled = true;
    if (any(cli_enable, rule.id)) enabled = true;
    else if (any(cli_disable, rule.id)) enabled = false;
    else if (config && any(config->enable, rule.id)) enabled = true;
    else if (config && any(config->disable, rule.id)) enabled = false;
    if (!enabled) off.emplace_back(rule.id);
  }
  return off;
}

void print_rules(std::ostream& out) {
  std::size_t width = 0;
  for (const auto& rule : bodyfmt::all_rules()) width = std::max(width, rule.id.size());
  for (const auto& rule : bodyfmt::all_rules())
    out << fmt::format("{:<{}}  {:<11}  {}\n", rule.id, width, bodyfmt::severity_name(rule.default_severity),
                       rule.summary);
}

bool same_diagnostic(const Diagnostic& a, const Diagnostic& b) {
  return a.location == b.location && a.rule_id == b.rule_id && a.message == b.message &&
         a.severity == b.severity;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Check Choreonoid .body models: located diagnostics as text, JSON or SARIF"};
  std::vector<std::string> inputs;
  std::string format = "text";
  std::string fail_on = "error";
  std::string output;
  std::vector<std::string> enable, disable;
  bool werror = false, quiet = false, stats = false, list_rules = false, no_meshes = false;
  bool no_config = false;
  std::size_t max_nodes = bodyfmt::LoadOptions{}.max_expanded_yaml_nodes;
  int jobs = 0;
  app.add_option("paths", inputs, "a .body file, or a directory searched recursively for *.body");
  app.add_option("--format", format, "output format")->check(CLI::IsMember({"text", "json", "sarif"}));
  auto* fail_on_opt = app.add_option("--fail-on", fail_on, "lowest severity that fails the run (default error)")
                          ->check(CLI::IsMember({"error", "warning"}));
  auto* werror_opt = app.add_flag("--werror", werror, "treat warnings as errors");
  app.add_option("--enable", enable, "enable a rule (or a family: units-*), over the config (repeatable)")
      ->allow_extra_args(false);
  app.add_option("--disable", disable, "disable a rule (or a family: units-*) (repeatable)")->allow_extra_args(false);
  app.add_flag("-q,--quiet", quiet, "print no note diagnostics and no summary line");
  app.add_flag("--stats", stats, "print the number of findings per rule");
  app.add_flag("--list-rules", list_rules, "list every rule with its default severity and exit");
  app.add_option("--max-yaml-nodes", max_nodes, "limit on YAML nodes after alias expansion");
  app.add_flag("--no-meshes", no_meshes, "do not import external mesh files");
  app.add_flag("--no-config", no_config, "ignore .bodycheck.yaml files");
  app.add_option("-o,--output", output, "write the report to this file instead of stdout");
  app.add_option("-j,--jobs", jobs, "worker threads (default: 2 to 4, by the cores available)")
      ->check(CLI::Range(1, 64));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return e.get_exit_code() == 0 ? 0 : 2;
  }

  if (list_rules) {
    print_rules(std::cout);
    return 0;
  }
  for (const auto* list : {&enable, &disable}) {
    for (const std::string& id : *list) {
      std::string problem = bodyfmt::check_rule_pattern(id);
      if (!problem.empty()) {
        std::cerr << "bodycheck: error: " << (list == &enable ? "--enable" : "--disable") << ": " << problem << '\n';
        return 2;
      }
    }
  }
  if (inputs.empty()) {
    std::cerr << "bodycheck: error: no input files (bodycheck --help)\n";
    return 2;
  }

  bool fatal = false;  // usage, I/O or fatal error: exit 2

  // Expand directories; keep the user's spelling of paths for the output.
  std::vector<std::string> files;
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (fs::is_directory(input, ec)) {
      std::vector<std::string> found;
      for (fs::recursive_directory_iterator it(input, fs::directory_options::skip_permission_denied, ec), end;
           !ec && it != end; it.increment(ec)) {
        if (it->path().extension() == ".body" && it->is_regular_file(ec)) found.push_back(it->path().string());
      }
      if (ec) {
        std::cerr << input << ": error: cannot read the directory: " << ec.message() << '\n';
        fatal = true;
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(input, ec)) {
      files.push_back(input);
    } else {
      std::cerr << input << ": error: no such file or directory\n";
      fatal = true;
    }
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());

  // Configs: the nearest .bodycheck.yaml per file, each read once.
  std::map<std::string, std::optional<bodyfmt::CheckConfig>> configs;
  bodyfmt::SourceLines sources;
  std::vector<Job> jobs_list;
  std::vector<Severity> fail_levels;
  for (const std::string& file : files) {
    const bodyfmt::CheckConfig* config = nullptr;
    if (!no_config) {
      const std::string path = bodyfmt::find_config(file);
      if (!path.empty()) {
        auto it = configs.find(path);
        if (it == configs.end()) {
          bodyfmt::CollectingSink config_sink;
          it = configs.emplace(path, bodyfmt::read_config(path, config_sink)).first;
          for (const Diagnostic& d : config_sink.diagnostics())
            std::cerr << bodyfmt::format_text_diagnostic(d, sources);
        }
        if (!it->second) {
          fatal = true;  // a malformed config: its files are not checked
          continue;
        }
        config = &*it->second;
      }
    }
    Job job;
    job.file = file;
    job.policy.disable = disabled_rules(disable, enable, config);
    job.policy.werror = werror_opt->count() > 0 ? werror : (config && config->werror ? *config->werror : false);
    Severity level = Severity::kError;
    if (fail_on_opt->count() > 0) level = fail_on == "warning" ? Severity::kWarning : Severity::kError;
    else if (config && config->fail_on) level = *config->fail_on;
    jobs_list.push_back(std::move(job));
    fail_levels.push_back(level);
  }

  // Check in parallel; each file's diagnostics are kept apart and merged in file order.
  bodyfmt::LoadOptions load_options;
  load_options.max_expanded_yaml_nodes = max_nodes;
  load_options.load_meshes = !no_meshes;
  std::vector<JobResult> results(jobs_list.size());
  unsigned threads = jobs > 0 ? static_cast<unsigned>(jobs)
                              : std::clamp(std::thread::hardware_concurrency(), 2u, 4u);
  threads = std::min<unsigned>(threads, static_cast<unsigned>(std::max<std::size_t>(jobs_list.size(), 1)));
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < jobs_list.size();) results[i] = check_file(jobs_list[i], load_options);
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }

  bodyfmt::Report report;
  bool findings = false;
  for (std::size_t i = 0; i < jobs_list.size(); ++i) {
    JobResult& r = results[i];
    report.files.push_back(jobs_list[i].file);
    report.suppressed += r.suppressed;
    report.disabled += r.disabled;
    if (!r.loaded) fatal = true;
    for (Diagnostic& d : r.diagnostics) {
      if (d.severity == Severity::kFatal) fatal = true;
      if (d.severity >= fail_levels[i]) findings = true;
      if (quiet && d.severity == Severity::kNote) continue;
      report.diagnostics.push_back(std::move(d));
    }
  }
  bodyfmt::sort_diagnostics(report.diagnostics);
  // A file included by several checked files (SubBody) reports the same finding each time.
  report.diagnostics.erase(std::unique(report.diagnostics.begin(), report.diagnostics.end(), same_diagnostic),
                           report.diagnostics.end());

  bodyfmt::ToolInfo tool;
  tool.version = BODYFMT_VERSION;
  tool.information_uri = BODYCHECK_INFORMATION_URI;
  std::string text;
  if (format == "json") {
    text = bodyfmt::format_json_report(report, tool);
  } else if (format == "sarif") {
    text = bodyfmt::format_sarif_report(report, tool);
  } else {
    text = bodyfmt::format_text_report(report, sources);
    if (!quiet) text += bodyfmt::format_summary_line(report);
  }
  if (stats) {
    std::string lines;
    for (const auto& [rule, n] : report.counts_by_rule()) lines += fmt::format("{:>6}  {}\n", n, rule);
    if (format == "text") text += lines;
    else std::cerr << lines;
  }
  if (output.empty()) {
    std::cout << text << std::flush;
  } else {
    std::ofstream out(output, std::ios::binary);
    out << text;
    out.close();
    if (!out) {
      std::cerr << output << ": error: cannot write the report\n";
      return 2;
    }
  }
  if (fatal) return 2;
  return findings ? 1 : 0;
}
