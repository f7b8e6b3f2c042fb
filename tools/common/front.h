#pragma once
/// The command-line front every bodyfmt tool shares: one spelling of the options that load a
/// model, set the diagnostic policy and print diagnostics, one way to read a model from a file
/// or from standard input, and one exit-code function. A tool's main adds its own options to
/// app(), calls parse(), and then uses the rest. A command with subcommands (bodysim) gives each
/// subcommand's CLI::App to its own Front, parses the whole command line itself, and calls
/// parsed() on the Front of the subcommand that ran.

#include "check_config.h"

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/diagnostic_policy.h>
#include <bodyfmt/load.h>
#include <bodyfmt/model.h>
#include <bodyfmt/report.h>

#include <CLI/CLI.hpp>

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace bodyfmt::tools {

/// The exit-code contract of every tool (docs/tools/README.md, "Exit codes").
enum ExitCode : int {
  kExitClean = 0,     ///< nothing at or above the fail level
  kExitFindings = 1,  ///< findings at or above the fail level
  kExitFatal = 2,     ///< usage, I/O or fatal error (for an exporter: nothing was written)
};

/// What decides a run's exit code besides fatal errors.
struct ExitPolicy {
  Severity fail_level = Severity::kError;  ///< --fail-on / .bodycheck.yaml
  /// Exporters: any `export-*` finding at warning or above (a lossy or renamed export) fails.
  bool export_warnings_fail = false;
  /// Exporters: kinds of `export-loss` accepted (--allow-loss): reported, but not failing.
  std::vector<std::string> allowed_losses;
};

/// True when `d` counts as a finding under `policy`.
bool is_finding(const Diagnostic& d, const ExitPolicy& policy);

/// The one exit-code function: kExitFatal when `fatal` (usage, I/O, nothing written) or any
/// diagnostic is fatal; kExitFindings when any diagnostic is a finding; else kExitClean.
int exit_code(const std::vector<Diagnostic>& diagnostics, const ExitPolicy& policy, bool fatal);

/// A model file named on the command line: a path, or "-" for standard input.
struct ModelInput {
  std::string path;  ///< as the user spelled it ("-" for standard input)
  std::string name;  ///< the name used in locations and to resolve relative URIs
  std::string text;  ///< the text, when it was read by the front (stdin, pipes, devices)
  bool read_by_front = false;
};

class Front {
 public:
  struct Features {
    bool many_inputs = false;  ///< files and directories (bodycheck); otherwise one model
    bool exporter = false;     ///< --strict and --best-effort, and `export-*` warnings fail the run
  };

  /// A front that owns its command line: one CLI::App named `tool_name`.
  Front(std::string tool_name, std::string description, Features features);
  /// A front that adds its options to `app`, which the caller owns and parses (a subcommand);
  /// `tool_name` is the name its messages start with.
  Front(std::string tool_name, CLI::App& app, Features features);
  Front(const Front&) = delete;  // CLI11 holds pointers to the members
  Front& operator=(const Front&) = delete;

  CLI::App& app() { return app_; }

  /// Parses the command line. Returns the exit code to stop with (0 after --help and
  /// --version, 2 for a usage error, printed) or nullopt to go on.
  std::optional<int> parse(int argc, char** argv);
  /// Completes the options after the caller has parsed the app given to the constructor.
  void parsed();

  const std::string& tool_name() const { return name_; }
  const std::vector<std::string>& inputs() const { return inputs_; }
  const LoadOptions& load_options() const { return load_options_; }
  bool quiet() const { return quiet_; }
  bool strict() const { return strict_; }
  /// Exporters: whether an output may be written after these diagnostics. Not when any is an
  /// error (a model with errors is not exported), unless --best-effort asks for it.
  bool may_write(const std::vector<Diagnostic>& diagnostics) const;
  bool no_config() const { return no_config_; }

  /// Reads the input `path` ("-": standard input, which can be read once). Regular files are
  /// left for the loader; standard input, pipes and devices (/dev/stdin, <(...)) are read here.
  /// Returns nullopt and reports `io-read` when the input cannot be read.
  std::optional<ModelInput> open_input(const std::string& path, DiagnosticSink& sink);

  /// Loads a model through `sink` (normally the DiagnosticPolicy of policy_for()).
  std::optional<Model> load(const ModelInput& input, DiagnosticSink& sink);

  /// The diagnostic policy for a model file: the command line over the nearest
  /// `.bodycheck.yaml` (found from `file`'s folder; standard input from the working folder).
  /// nullopt when that config is malformed (its diagnostics are printed).
  struct FilePolicy {
    PolicyOptions options;
    ExitPolicy exit;
  };
  std::optional<FilePolicy> policy_for(const std::string& file);

  /// Text options for printing: source lines and carets always, notes unless -q, colour from
  /// --color (auto: when stderr is a terminal and NO_COLOR is unset).
  TextOptions text_options(bool to_terminal_stream) const;
  SourceLines& sources() { return sources_; }

  /// Sorts `diagnostics` and prints them to stderr in the text format.
  void print(std::vector<Diagnostic> diagnostics);

  /// Prints `tool: error: message` to stderr (usage and I/O problems with no location).
  void print_error(const std::string& message) const;

 private:
  void add_options();

  std::string name_;
  Features features_;
  std::unique_ptr<CLI::App> owned_app_;  // null when the caller owns the app
  CLI::App& app_;
  std::vector<std::string> inputs_;
  std::string stdin_filename_;
  LoadOptions load_options_;
  std::vector<std::string> package_paths_;
  bool no_ros_package_path_ = false;
  bool no_meshes_ = false;
  std::vector<std::string> enable_, disable_;
  std::vector<std::string> severities_;  ///< --severity RULE=LEVEL, checked when parsed
  std::string fail_on_;
  bool werror_ = false;
  bool quiet_ = false;
  bool no_config_ = false;
  bool strict_ = false;
  bool best_effort_ = false;
  std::vector<std::string> allowed_losses_;
  std::string color_ = "auto";
  CLI::Option* fail_on_option_ = nullptr;
  CLI::Option* werror_option_ = nullptr;
  std::map<std::string, std::optional<CheckConfig>> configs_;
  SourceLines sources_;
  std::mutex sources_mutex_;  ///< loads on worker threads add to sources_
};

}  // namespace bodyfmt::tools
