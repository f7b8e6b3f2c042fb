#include "front.h"

#include "help_formatter.h"
#include "model_file_readers.h"
#include "number_options.h"

#include <bodyfmt/input_files.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#ifndef BODYFMT_VERSION
#error "BODYFMT_VERSION comes from CMake (project version)"
#endif

namespace bodyfmt::tools {

bool is_finding(const Diagnostic& d, const ExitPolicy& policy) {
  if (d.severity >= policy.fail_level) return true;
  if (!policy.export_warnings_fail || d.severity < Severity::kWarning || d.rule_id.rfind("export-", 0) != 0)
    return false;
  const bool allowed =
      d.rule_id == "export-loss" &&
      std::find(policy.allowed_losses.begin(), policy.allowed_losses.end(), d.category) != policy.allowed_losses.end();
  return !allowed;
}

int exit_code(const std::vector<Diagnostic>& diagnostics, const ExitPolicy& policy, bool fatal) {
  bool findings = false;
  for (const Diagnostic& d : diagnostics) {
    fatal = fatal || d.severity == Severity::kFatal;
    findings = findings || is_finding(d, policy);
  }
  if (fatal) return kExitFatal;
  return findings ? kExitFindings : kExitClean;
}

namespace {

/// Rule ids switched off by the layered settings: command line over config, and within each,
/// enable over disable.
std::vector<std::string> disabled_rules(const std::vector<std::string>& cli_disable,
                                        const std::vector<std::string>& cli_enable, const CheckConfig* config) {
  auto any = [](const std::vector<std::string>& patterns, std::string_view id) {
    return std::any_of(patterns.begin(), patterns.end(),
                       [&](const std::string& p) { return rule_pattern_matches(p, id); });
  };
  std::vector<std::string> off;
  for (const RuleInfo& rule : all_rules()) {
    bool enabled = true;
    if (any(cli_enable, rule.id))
      enabled = true;
    else if (any(cli_disable, rule.id))
      enabled = false;
    else if (config && any(config->enable, rule.id))
      enabled = true;
    else if (config && any(config->disable, rule.id))
      enabled = false;
    if (!enabled) off.emplace_back(rule.id);
  }
  return off;
}

/// A CLI11 validator for rule ids and `family-*` patterns, with a did-you-mean.
std::string check_patterns(const std::string& value) { return check_rule_pattern(value); }

/// The name the standard-output check below reports under (the first Front's).
std::string g_stdout_owner;

/// Every tool's main output may go to standard output (a report, a canonical text, an export
/// to '-', --help), and a full disk or an I/O error there must not end in exit 0 or 1. Run at
/// exit, after main has returned its code: the one place that sees every return path.
void check_stdout_at_exit() {
  errno = 0;
  std::cout.flush();  // through stdio: fails with stdout's buffer, and sets errno
  int error = errno;
  if (std::fflush(stdout) != 0) error = errno;
  if (std::cout.good() && std::ferror(stdout) == 0) return;
  // errno is the reason when this flush failed; an earlier write's reason is long gone.
  std::fprintf(stderr, "%s: error: cannot write to standard output%s%s\n", g_stdout_owner.c_str(),
               error != 0 ? ": " : "", error != 0 ? std::strerror(error) : "");
  std::_Exit(kExitFatal);  // the exit code main returned would claim the output was written
}

void watch_stdout(const std::string& tool_name) {
  if (!g_stdout_owner.empty()) return;
  g_stdout_owner = tool_name;
  std::atexit(check_stdout_at_exit);
}

/// `RULE=LEVEL` of --severity, split at the last '='.
std::pair<std::string, std::string> split_severity(const std::string& value) {
  const std::size_t equals = value.rfind('=');
  if (equals == std::string::npos) return {value, ""};
  return {value.substr(0, equals), value.substr(equals + 1)};
}

std::string check_severity(const std::string& value) {
  const auto [rule, level] = split_severity(value);
  if (value.find('=') == std::string::npos) return "expected RULE=LEVEL, e.g. joint-id-on-fixed=error";
  const std::string problem = check_rule_pattern(rule);
  if (!problem.empty()) return problem;
  if (!parse_rule_severity(level)) return "the level of " + rule + " must be note, warning or error";
  return {};
}

bool regular_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace

Front::Front(std::string tool_name, std::string description, Features features)
    : name_(std::move(tool_name)),
      features_(features),
      owned_app_(std::make_unique<CLI::App>(std::move(description), name_)),
      app_(*owned_app_) {
  watch_stdout(name_);
  add_options();
}

Front::Front(std::string tool_name, CLI::App& app, Features features)
    : name_(std::move(tool_name)), features_(features), app_(app) {
  watch_stdout(name_.substr(0, name_.find(' ')));
  add_options();
}

void Front::add_options() {
  // Reports quote the files the loader read as model text, and no other (issue 45). Loads
  // may run on worker threads.
  load_options_.on_model_text = [this](const std::string& path) {
    const std::lock_guard<std::mutex> lock(sources_mutex_);
    sources_.add_file(path);
  };
  app_.formatter(help_formatter());
  app_.set_version_flag("--version", name_ + " " + BODYFMT_VERSION, "print the version and exit");
  if (features_.many_inputs) {
    app_.add_option("paths", inputs_,
                    "a .body file, a directory searched recursively for *.body, or - for standard input");
  } else {
    app_.add_option("file", inputs_, "the .body file, or - for standard input")->required()->expected(1);
  }
  app_.add_option("--stdin-filename", stdin_filename_,
                  "the file name used for standard input in locations and to resolve its relative URIs");

  const std::string loading = "Loading";
  const CLI::Validator positive = whole_number_above_zero();
  app_.add_option("--package-path", package_paths_, "a folder holding ROS packages for package:// URIs (repeatable)")
      ->allow_extra_args(false)
      ->group(loading);
  app_.add_flag("--no-ros-package-path", no_ros_package_path_, "do not search ROS_PACKAGE_PATH for package:// URIs")
      ->group(loading);
  app_.add_flag("--no-meshes", no_meshes_, "do not import external mesh files")->group(loading);
  app_.add_option("--max-yaml-nodes", load_options_.max_expanded_yaml_nodes,
                  "limit on YAML nodes after alias expansion")
      ->check(positive)
      ->group(loading);
  app_.add_option("--max-yaml-depth", load_options_.max_yaml_depth, "limit on YAML nesting depth")
      ->check(positive)
      ->group(loading);
  app_.add_option("--max-file-size", load_options_.max_file_bytes,
                  "largest file read, in bytes (the model, SubBody and YAML resources, meshes; default 256 MiB)")
      ->check(positive)
      ->group(loading);
  app_.add_option("--max-mesh-triangles", load_options_.max_mesh_triangles,
                  "most triangles of a binary STL mesh imported (default 1000000)")
      ->check(positive)
      ->group(loading);

  const std::string policy = "Diagnostics";
  app_.add_option("--enable", enable_,
                  "enable a rule (or a family: units-*), over .bodycheck.yaml (repeatable, or comma-separated)")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->check(check_patterns, "RULE")
      ->group(policy);
  app_.add_option("--disable", disable_, "disable a rule (or a family: units-*) (repeatable, or comma-separated)")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->check(check_patterns, "RULE")
      ->group(policy);
  app_.add_option("--severity", severities_,
                  "give a rule (or a family) a severity: RULE=note, RULE=warning or RULE=error, over .bodycheck.yaml "
                  "(repeatable, or comma-separated)")
      ->allow_extra_args(false)
      ->delimiter(',')
      ->check(check_severity, "RULE=LEVEL")
      ->group(policy);
  fail_on_option_ = app_.add_option("--fail-on", fail_on_, "lowest severity that fails the run (default error)")
                        ->check(CLI::IsMember({"error", "warning"}))
                        ->group(policy);
  werror_option_ = app_.add_flag("--werror", werror_, "treat warnings as errors")->group(policy);
  app_.add_flag("--no-config", no_config_, "ignore .bodycheck.yaml files")->group(policy);
  if (features_.exporter) {
    app_.add_flag("--strict", strict_,
                  "treat every export loss and every value the export changes as an error: nothing is written")
        ->group(policy);
    app_.add_option("--allow-loss", allowed_losses_,
                    "kinds of loss to accept: still reported, but the exit code stays 0 when only these were lost ("
                    "comma-separated: tracks, closed-loops, devices, textures, materials, geometry, joints, dynamics)")
        ->allow_extra_args(false)
        ->delimiter(',')
        ->check(CLI::IsMember(
            {"tracks", "closed-loops", "devices", "textures", "materials", "geometry", "joints", "dynamics"}))
        ->group(policy);
    app_.add_flag("--best-effort", best_effort_,
                  "write the output even when the model has errors (the exit code stays 1)")
        ->group(policy);
  }
  app_.add_flag("-q,--quiet", quiet_, "print no notes: neither note diagnostics nor the notes attached to others")
      ->group(policy);
  app_.add_option("--color", color_, "colour the diagnostics: auto (a terminal, unless NO_COLOR is set), always, never")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->group(policy);
}

std::optional<int> Front::parse(int argc, char** argv) {
  try {
    app_.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app_.exit(e);
    return code == 0 ? kExitClean : kExitFatal;
  }
  parsed();
  return std::nullopt;
}

void Front::parsed() {
  load_options_.package_paths = package_paths_;
  load_options_.use_ros_package_path = !no_ros_package_path_;
  load_options_.load_meshes = !no_meshes_;
  add_model_file_readers(load_options_);  // wrapper body files naming a URDF
}

std::optional<ModelInput> Front::open_input(const std::string& path, DiagnosticSink& sink) {
  ModelInput input;
  input.path = path;
  input.name = path == "-" ? (stdin_filename_.empty() ? std::string("<stdin>") : stdin_filename_) : path;
  if (path != "-" && regular_file(path)) return input;  // the loader reads it
  // Standard input, a pipe (<(...)), or a device: read once, here, so that the text is also
  // there for the source lines of the report.
  struct stat st {};
  if (path != "-" && ::stat(path.c_str(), &st) != 0) {
    // Nothing to read (missing, a symbolic link loop...): the bounded reader says why.
    std::string why;
    readable_regular_file(path, load_options_.max_file_bytes, why);
    report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "cannot read \"" + path + "\": " + why);
    return std::nullopt;
  }
  if (path != "-" && S_ISDIR(st.st_mode)) {
    report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "\"" + path + "\" is a directory, not a .body file");
    return std::nullopt;
  }
  if (path == "-") note_standard_input_read();
  std::ifstream file;
  if (path != "-") file.open(path, std::ios::binary);
  std::istream& in = path == "-" ? std::cin : file;
  // At most the file-size limit, plus one byte to tell that the limit was crossed.
  std::string text;
  const std::uintmax_t limit = load_options_.max_file_bytes;
  char buffer[65536];
  while (in && text.size() <= limit) {
    in.read(buffer, static_cast<std::streamsize>(std::min<std::uintmax_t>(sizeof buffer, limit + 1 - text.size())));
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if ((path != "-" && !file.is_open()) || in.bad()) {
    report_rule(sink, "io-read", SourceLocation{input.name, 0, 0}, "cannot read \"" + path + "\"");
    return std::nullopt;
  }
  if (text.size() > limit) {
    report_rule(sink, "io-read", SourceLocation{input.name, 0, 0},
                "\"" + path + "\" is larger than the limit of " + std::to_string(limit) + " bytes (--max-file-size)");
    return std::nullopt;
  }
  input.text = std::move(text);
  input.read_by_front = true;
  sources_.add(input.name, input.text);
  return input;
}

std::optional<Model> Front::load(const ModelInput& input, DiagnosticSink& sink) {
  if (input.read_by_front) return load_body_string(input.text, input.name, load_options_, sink);
  return load_body(input.path, load_options_, sink);
}

std::optional<Front::FilePolicy> Front::policy_for(const std::string& file) {
  const CheckConfig* config = nullptr;
  if (!no_config_) {
    const std::string path = find_config(file == "-" || file.rfind('<', 0) == 0 ? std::string("./x") : file);
    if (!path.empty()) {
      auto it = configs_.find(path);
      if (it == configs_.end()) {
        CollectingSink config_sink;
        it = configs_.emplace(path, read_config(path, config_sink)).first;
        print(std::move(config_sink.diagnostics()));
      }
      if (!it->second) return std::nullopt;
      config = &*it->second;
    }
  }
  FilePolicy policy;
  policy.options.disable = disabled_rules(disable_, enable_, config);
  if (config) policy.options.severities = config->severity;
  for (const std::string& value : severities_) {
    const auto [rule, level] = split_severity(value);
    policy.options.severities.emplace_back(rule, *parse_rule_severity(level));
  }
  policy.options.werror = werror_option_->count() > 0 ? werror_ : (config && config->werror && *config->werror);
  policy.options.strict = strict_;
  if (fail_on_option_->count() > 0)
    policy.exit.fail_level = fail_on_ == "warning" ? Severity::kWarning : Severity::kError;
  else if (config && config->fail_on)
    policy.exit.fail_level = *config->fail_on;
  policy.exit.export_warnings_fail = features_.exporter;
  policy.exit.allowed_losses = allowed_losses_;
  return policy;
}

TextOptions Front::text_options(bool to_terminal_stream) const {
  TextOptions options;
  options.notes = !quiet_;
  if (color_ == "always")
    options.color = true;
  else if (color_ == "auto")
    options.color = to_terminal_stream && std::getenv("NO_COLOR") == nullptr;
  return options;
}

void Front::print(std::vector<Diagnostic> diagnostics) {
  sort_diagnostics(diagnostics);
  const TextOptions options = text_options(::isatty(STDERR_FILENO) != 0);
  std::string text;
  for (const Diagnostic& d : diagnostics) {
    if (d.severity == Severity::kNote && !options.notes) continue;
    text += format_text_diagnostic(d, sources_, options);
  }
  std::cerr << text << std::flush;
}

bool Front::may_write(const std::vector<Diagnostic>& diagnostics) const {
  for (const Diagnostic& d : diagnostics) {
    if (d.severity == Severity::kFatal) return false;
    if (d.severity == Severity::kError && !best_effort_) return false;
  }
  return true;
}

void Front::print_error(const std::string& message) const { std::cerr << name_ << ": error: " << message << '\n'; }

}  // namespace bodyfmt::tools
