#include "load/scalar.h"

#include "text/text_util.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string_view>

namespace bodyfmt::detail {
namespace {

bool is_scalar(LoadContext& ctx, const yaml::NodeRef& ref, const char* what) {
  if (ref && ref->is_scalar()) return true;
  ctx.report("load-type", ref,
             std::string("expected ") + what + ", found a " + (ref && ref->is_mapping() ? "mapping" : "sequence"));
  return false;
}

/// NaN and infinity (also from an overflowing literal such as 1e999) load in Choreonoid but
/// break every simulator and exporter: an error, saying why.
bool report_if_not_finite(LoadContext& ctx, const yaml::NodeRef& ref, double value) {
  if (std::isfinite(value)) return false;
  ctx.report("load-number", ref,
             "the value \"" + std::string(ref->scalar()) + "\" is not finite (" +
                 (std::isnan(value) ? "NaN" : "infinite") + "); masses, lengths and angles must be finite numbers");
  return true;
}

}  // namespace

std::optional<double> required_double(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!is_scalar(ctx, ref, "a number")) return std::nullopt;
  const std::string_view text = ref->scalar();
  if (auto value = parse_plain_decimal(text)) return value;  // finite and whole: nothing to report
  const char* begin = text.data();                           // NUL-terminated
  char* end = nullptr;
  double value = std::strtod(begin, &end);
  if (is_yaml_special_float(text)) {
    ctx.report("load-number", ref,
               "the value \"" + std::string(text) + "\" is not finite (YAML's " +
                   (text.find('n') != std::string::npos || text.find('N') != std::string::npos ? "NaN" : "infinity") +
                   "); Choreonoid cannot read it, and masses, lengths and angles must be finite numbers");
    return std::nullopt;
  }
  if (end == begin) {
    ctx.report("load-number", ref, "the value \"" + std::string(text) + "\" must be a floating point number");
    return std::nullopt;
  }
  if (!only_trailing_space(end)) {
    // body-format-spec §1.2: Choreonoid reads "0.t" as 0 (strtod prefix); we load the same
    // value and warn, since the text is almost certainly a typo.
    const std::string prefix(begin, static_cast<std::size_t>(end - begin));
    ctx.report("load-lenient-number", ref,
               "\"" + std::string(text) + "\" is not a number; Choreonoid reads its prefix " + prefix +
                   " and ignores \"" + std::string(end) + "\"",
               "write the number in full, e.g. " + prefix);
  }
  if (report_if_not_finite(ctx, ref, value)) return std::nullopt;
  return value;
}

std::optional<long> required_int(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!is_scalar(ctx, ref, "an integer")) return std::nullopt;
  const std::string_view text = ref->scalar();
  const char* begin = text.data();  // NUL-terminated
  char* end = nullptr;
  errno = 0;
  long value = std::strtol(begin, &end, 10);
  if (end == begin) {
    ctx.report("load-number", ref, "the value \"" + std::string(text) + "\" must be an integer value");
    return std::nullopt;
  }
  if (!only_trailing_space(end)) {
    ctx.report("load-lenient-number", ref,
               "\"" + std::string(text) + "\" is not an integer; Choreonoid reads it as " + std::to_string(value),
               "write " + std::to_string(value));
  }
  return value;
}

std::optional<bool> required_bool(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!is_scalar(ctx, ref, "a boolean")) return std::nullopt;
  auto value = text::parse_bool_word(ref->scalar());
  if (!value) ctx.report("load-bool", ref, "the value \"" + std::string(ref->scalar()) + "\" must be a boolean value");
  return value;
}

std::optional<std::string> required_string(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (!is_scalar(ctx, ref, "a string")) return std::nullopt;
  return std::string(ref->scalar());
}

std::optional<double> optional_double(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (ref && ref->is_scalar()) {
    if (auto value = parse_double_exact(ref->scalar())) {
      if (report_if_not_finite(ctx, ref, *value)) return std::nullopt;
      return value;
    }
    if (is_yaml_special_float(ref->scalar())) {
      ctx.report("load-number", ref,
                 "the value \"" + std::string(ref->scalar()) +
                     "\" is not finite; Choreonoid cannot read it and silently uses the default");
      return std::nullopt;
    }
  }
  ctx.report("load-ignored-value", ref, "this value is not a number; Choreonoid ignores it and uses the default");
  return std::nullopt;
}

std::optional<long> optional_int(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (ref && ref->is_scalar()) {
    const char* text = ref->scalar().data();  // NUL-terminated
    char* end = nullptr;
    long value = std::strtol(text, &end, 10);
    if (end != text && only_trailing_space(end)) return value;
  }
  ctx.report("load-ignored-value", ref, "this value is not an integer; Choreonoid ignores it and uses the default");
  return std::nullopt;
}

std::optional<bool> optional_bool(LoadContext& ctx, const yaml::NodeRef& ref) {
  if (ref && ref->is_scalar()) {
    if (auto value = text::parse_bool_word(ref->scalar())) return value;
  }
  ctx.report("load-ignored-value", ref, "this value is not a boolean; Choreonoid ignores it and uses the default");
  return std::nullopt;
}

}  // namespace bodyfmt::detail
