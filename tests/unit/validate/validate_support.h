#pragma once
// Shared by the validator tests: load a file, derive, check, and collect every diagnostic of
// the three stages in one list (what bodycheck reports).

#include <bodyfmt/derived.h>
#include <bodyfmt/load.h>
#include <bodyfmt/validate.h>

#include <string>
#include <vector>

namespace bodyfmt::test {

struct CheckResult {
  bool loaded = false;
  std::vector<Diagnostic> diagnostics;
};

inline CheckResult check_file(const std::string& path) {
  CollectingSink sink;
  CheckResult result;
  LoadOptions options;
  std::optional<Model> model = load_body(path, options, sink);
  if (model) {
    result.loaded = true;
    const Derived derived = compute_derived(*model, sink);
    validate::check_model(*model, derived, validate::CheckOptions{}, sink);
  }
  result.diagnostics = sink.diagnostics();
  return result;
}

}  // namespace bodyfmt::test
