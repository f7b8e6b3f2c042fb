#include <bodyfmt/converters/loss.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <array>

namespace bodyfmt::converters {

namespace {
constexpr std::array<std::pair<LossKind, std::string_view>, 8> kKinds = {{
    {LossKind::kTracks, "tracks"},
    {LossKind::kExtraJoints, "closed-loops"},
    {LossKind::kDevices, "devices"},
    {LossKind::kTextures, "textures"},
    {LossKind::kMaterials, "materials"},
    {LossKind::kGeometry, "geometry"},
    {LossKind::kJoints, "joints"},
    {LossKind::kDynamics, "dynamics"},
}};
}  // namespace

std::string_view loss_kind_name(LossKind kind) {
  for (const auto& [k, name] : kKinds)
    if (k == kind) return name;
  return "geometry";
}

std::optional<LossKind> parse_loss_kind(std::string_view name) {
  for (const auto& [k, n] : kKinds)
    if (n == name) return k;
  return std::nullopt;
}

std::string loss_kind_names() {
  std::string names;
  for (const auto& [k, name] : kKinds) names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}

void report_loss(DiagnosticSink& sink, const SourceLocation& location, std::string_view target, LossKind kind,
                 std::string_view what, std::string_view hint) {
  Diagnostic d = make_diagnostic(
      "export-loss", location, fmt::format("{} cannot express {} (loss kind: {})", target, what, loss_kind_name(kind)),
      std::string(hint));
  d.category = std::string(loss_kind_name(kind));
  sink.report(std::move(d));
}

}  // namespace bodyfmt::converters
