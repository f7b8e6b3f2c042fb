#pragma once
// Shared by the tessellate*.cpp files only.

#include <bodyfmt/tessellate.h>

#include <cstddef>
#include <string>
#include <vector>

namespace bodyfmt::detail {

/// Reports geometry problems at the shape's location. Caps the number of diagnostics per
/// geometry so that a face list with a million bad indices stays readable.
class Reporter {
 public:
  Reporter(DiagnosticSink& sink, const SourceLocation& where) : sink_(sink), where_(where) {}
  ~Reporter();
  Reporter(const Reporter&) = delete;
  Reporter& operator=(const Reporter&) = delete;

  void report(const char* rule_id, std::string message);

 private:
  static constexpr int kMaxReports = 10;
  DiagnosticSink& sink_;
  const SourceLocation& where_;
  int reported_ = 0;
  int suppressed_ = 0;
  std::string first_suppressed_;  ///< rule id of the first diagnostic left out
};

constexpr const char* kRuleInvalidSize = "geometry-invalid-size";
constexpr const char* kRuleDegenerate = "geometry-degenerate";
constexpr const char* kRuleIndexOutOfRange = "geometry-index-out-of-range";

TriangleMesh tessellate_extrusion(const Extrusion& extrusion, ExtrusionFrames frames, Reporter& reporter);

/// `mesh`, tessellated from `geometry` with `n` divisions, with texture coordinates as
/// tessellate() documents them; vertices are split where corners need different ones. For a
/// face list, `origins` holds per triangle where in `faces` its polygon (or triangle) starts.
/// Returns `mesh` unchanged where no texture coordinates can be given.
TriangleMesh with_tex_coords(const TriangleMesh& mesh, const Geometry& geometry, int n,
                             const std::vector<std::size_t>& origins);

/// Reverses every triangle (inside-out -> outside-out).
void flip_triangles(TriangleMesh& mesh);

}  // namespace bodyfmt::detail
