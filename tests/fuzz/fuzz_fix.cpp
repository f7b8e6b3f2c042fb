// libFuzzer target: bodycheck --fix's edits on one model file (issue 26). The fix-its the
// loader proposes (safe, and the format upgrade) are applied as bodycheck --fix applies them:
// all together, or, when the re-load differs, without the units that change the model by
// themselves. Oracles: the fixed text loads to the same model, and fixing it again changes
// nothing.
#include <bodyfmt/fix.h>
#include <bodyfmt/load.h>

#include <cstdio>
#include <cstdlib>

namespace {

constexpr const char* kFile = "/fuzz/main.body";  // never read: the text is given

bodyfmt::LoadOptions options() {
  bodyfmt::LoadOptions o;
  o.max_expanded_yaml_nodes = 200'000;
  o.max_yaml_depth = 64;
  o.load_meshes = false;
  return o;
}

struct Loaded {
  std::optional<bodyfmt::Model> model;
  std::vector<std::vector<bodyfmt::FixIt>> units;  // each safe fix-it alone, the upgrade whole
};

Loaded load(const std::string& text) {
  bodyfmt::CollectingSink sink;
  Loaded out;
  out.model = bodyfmt::load_body_string(text, kFile, options(), sink);
  for (const bodyfmt::Diagnostic& d : sink.diagnostics()) {
    if (d.severity == bodyfmt::Severity::kFatal) out.model.reset();
    std::vector<bodyfmt::FixIt> upgrade;
    for (const bodyfmt::FixIt& f : d.fixes) {
      if (f.file.str() != kFile) continue;
      if (f.safety == bodyfmt::FixSafety::kUpgrade)
        upgrade.push_back(f);
      else if (f.safety == bodyfmt::FixSafety::kSafe)
        out.units.push_back({f});
    }
    if (!upgrade.empty()) out.units.push_back(upgrade);
  }
  return out;
}

/// The text with `units` applied, if it applies and loads to `model`.
std::optional<std::string> fixed(const std::string& text, const std::vector<std::vector<bodyfmt::FixIt>>& units,
                                 const bodyfmt::Model& model) {
  std::vector<bodyfmt::FixIt> all;
  for (const auto& unit : units) all.insert(all.end(), unit.begin(), unit.end());
  std::string why;
  std::optional<std::string> after = bodyfmt::apply_fixes(text, all, why);
  if (!after) return std::nullopt;
  const Loaded again = load(*after);
  if (!again.model || bodyfmt::model_difference(model, *again.model)) return std::nullopt;
  return after;
}

/// What bodycheck --fix writes: every unit, or those that keep the model by themselves.
std::optional<std::string> fix(const std::string& text, const Loaded& loaded) {
  if (auto all = fixed(text, loaded.units, *loaded.model)) return all;
  std::vector<std::vector<bodyfmt::FixIt>> kept;
  for (const auto& unit : loaded.units)
    if (fixed(text, {unit}, *loaded.model)) kept.push_back(unit);
  return fixed(text, kept, *loaded.model);
}

[[noreturn]] void fail(const char* what, const std::string& before, const std::string& after) {
  std::fprintf(stderr, "%s\n--- before\n%s\n--- after\n%s\n", what, before.c_str(), after.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const Loaded loaded = load(text);
  if (!loaded.model || loaded.units.empty() || loaded.units.size() > 64) return 0;
  const std::optional<std::string> once = fix(text, loaded);
  if (!once) {
    // Units that each keep the model but not together (two edits overlap): bodycheck refuses
    // the file, which is allowed; what it writes is checked below.
    return 0;
  }
  const Loaded second = load(*once);
  if (!second.model) fail("the fixed text does not load", text, *once);
  if (auto difference = bodyfmt::model_difference(*loaded.model, *second.model))
    fail(("the fixed text loads another model: " + *difference).c_str(), text, *once);
  if (second.units.empty()) return 0;
  const std::optional<std::string> twice = fix(*once, second);
  if (twice && *twice != *once) fail("a second fix changes the text", *once, *twice);
  return 0;
}
