#include "model_screening.h"

#include "simbody_contact_shapes.h"

#include <bodyfmt/rules.h>
#include <bodyfmt/validate.h>

#include <fmt/format.h>

#include <utility>
#include <vector>

namespace bodyfmt::tools {

namespace {

/// bodycheck's rules under bodysim's policy, except the inertia findings that Simulation::build
/// reports itself with what it does about them (refused, or balanced with --balance-inertia).
/// An asymmetric tensor is simulated symmetrised (Simulation and body2mjcf's writer take
/// (I + Iᵀ)/2, the mean of each off-diagonal pair): with --balance-inertia that is a balance
/// like the others, said at the tensor's line; without it, bodycheck's error.
class ValidatorFirst : public DiagnosticSink {
 public:
  ValidatorFirst(DiagnosticSink& inner, bool balance) : inner_(inner), balance_(balance) {}
  void report(Diagnostic d) override {
    if (d.rule_id == "inertia-triangle" || d.rule_id == "inertia-not-positive-definite") {
      held_.push_back(std::move(d));
      return;
    }
    if (balance_ && d.rule_id == "inertia-asymmetric") {
      report_rule(inner_, "dynamics-inertia-balanced", d.location,
                  d.message +
                      "; simulated with --balance-inertia as the symmetrised tensor, the mean of each "
                      "off-diagonal pair (Choreonoid uses the 9 numbers as given)",
                  "write the 6-element form [Ixx, Ixy, Ixz, Iyy, Iyz, Izz] with the values you mean");
      return;
    }
    inner_.report(std::move(d));
  }
  /// When another error stops the run before Simulation::build, the inertia findings it would
  /// have reported are bodycheck's: every finding is said before bodysim refuses, as bodycheck
  /// says them on the file. (With --balance-inertia they are not errors of this run.)
  void release_held() {
    if (!balance_)
      for (Diagnostic& d : held_) inner_.report(std::move(d));
    held_.clear();
  }

 private:
  DiagnosticSink& inner_;
  bool balance_;
  std::vector<Diagnostic> held_;
};

}  // namespace

Screening screen_model(const Model& model, const SimCommand& command, RunDiagnostics& run) {
  const dynamics::SimOptions& sim = command.suite.sim;
  DiagnosticSink& sink = run.sink();
  const CollectingSink& collected = run.collected();
  Screening screening;
  if (collected.error_count() > 0) {
    screening.refusal = "the model has errors; nothing was simulated";
    return screening;
  }
  if (model.links.size() > command.max_links) {
    const Link& first_over = model.links[command.max_links];
    report_rule(sink, "dynamics-model-size", source_of(first_over, LinkSources::kName),
                fmt::format("the model has {} links, more than bodysim simulates (--max-links {}); this is link {}, "
                            "the first over the limit",
                            model.links.size(), command.max_links, command.max_links + 1),
                "raise --max-links to simulate it anyway; 100 links take seconds, 300 links about half a minute");
    screening.refusal = "the model is too large to simulate; nothing was simulated";
    return screening;
  }
  Derived derived = compute_derived(model, sink);
  // The validator first: what bodycheck calls an error (a reversed range, a moving massless
  // link, ...) is refused at its line before any engine sees it.
  {
    ValidatorFirst validator(sink, sim.balance_inertia);
    validate::check_model(model, derived, {}, validator);
    if (collected.error_count() > 0) validator.release_held();
  }
  if (collected.error_count() > 0) {
    screening.refusal = "the model has errors (bodycheck's rules); nothing was simulated";
    return screening;
  }
  if (sim.contact_model == dynamics::ContactModel::kSimbody && !simbody_takes_contact_shapes(model, sink)) {
    screening.refusal = "--contact simbody cannot simulate this model; nothing was simulated";
    return screening;
  }
  screening.derived = std::move(derived);
  return screening;
}

}  // namespace bodyfmt::tools
