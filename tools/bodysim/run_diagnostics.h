#pragma once
/// The diagnostics of one bodysim run under its file's policy, and how the run ends: every
/// diagnostic printed, then the reason it stopped, and the exit code.

#include "front.h"

#include <bodyfmt/diagnostic.h>
#include <bodyfmt/diagnostic_policy.h>

#include <string>

namespace bodyfmt::tools {

class RunDiagnostics {
 public:
  RunDiagnostics(Front& front, const Front::FilePolicy& policy);
  RunDiagnostics(const RunDiagnostics&) = delete;  // the policy sink points at the collection
  RunDiagnostics& operator=(const RunDiagnostics&) = delete;

  /// Where the run reports (the file's policy over the collection).
  DiagnosticSink& sink() { return sink_; }
  const CollectingSink& collected() const { return collected_; }

  /// Prints the diagnostics and `why` (empty: nothing more to say) and returns the exit code;
  /// `fatal` when the run did not do what it was asked.
  int finish(bool fatal, const std::string& why);

 private:
  Front& front_;
  ExitPolicy exit_;
  CollectingSink collected_;
  DiagnosticPolicy sink_;
};

}  // namespace bodyfmt::tools
