#include <bodyfmt/validate.h>

namespace bodyfmt::validate {

void check_model(const Model&, const Derived&, const CheckOptions&, DiagnosticSink&) {}

}  // namespace bodyfmt::validate
