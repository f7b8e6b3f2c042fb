// urdf2body: imports a URDF into a canonical Choreonoid .body file (format 2.0).
// Exit codes (tools/common/front.h): 0 written with nothing lost; 1 written, with losses or
// other findings reported; 2 not written (bad usage, a URDF that does not read or has errors,
// a mesh that cannot be found, or --strict losses).

#include "export_run.h"
#include "front.h"
#include "number_options.h"
#include "urdf_reader.h"

#include <bodyfmt/body_writer.h>
#include <bodyfmt/converters/output_set.h>
#include <bodyfmt/converters/staged_files.h>
#include <bodyfmt/geometry_mass.h>
#include <bodyfmt/mesh_import.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {

namespace fs = std::filesystem;

// The URDF's text: from the front for standard input and pipes, else from the file through
// the bounded reader, up to the --max-file-size limit (reported as io-read beyond it).
std::optional<std::string> read_text(const bodyfmt::tools::ModelInput& input, std::uintmax_t limit,
                                     bodyfmt::DiagnosticSink& sink) {
  if (input.read_by_front) return input.text;
  std::string why;
  std::optional<std::string> text = bodyfmt::read_regular_file(input.path, limit, why);
  if (!text)
    bodyfmt::report_rule(sink, "io-read", bodyfmt::SourceLocation{input.name, 0, 0},
                         "cannot read \"" + input.path + "\": " + why);
  return text;
}

// Stages a copy of every resolved mesh in the output's mesh folder (each file once) and points
// its shapes at the copy. Only a mesh the mesh importer reads is copied (a located error
// otherwise), through the bounded reader: a 5 GB file is refused, not read whole.
void copy_mesh_files(bodyfmt::Model& model, bodyfmt::converters::OutputSet& out, const bodyfmt::LoadOptions& limits,
                     bodyfmt::DiagnosticSink& sink) {
  using namespace bodyfmt;
  converters::StagedFiles staged(out, converters::generated_folder("", "meshes", out, model.name));
  MeshCache meshes;
  MeshImportOptions import;
  import.max_file_bytes = limits.max_file_bytes;
  import.max_triangles = limits.max_mesh_triangles;
  for (Link& link : model.links)
    for (Shape& shape : link.shapes)
      if (auto* mesh = geometry_if<MeshResource>(shape.geometry); mesh && !mesh->resolved_path.empty()) {
        if (!meshes.get(mesh->resolved_path, import, sink, mesh->uri_source)) continue;
        std::string error;
        if (auto relative = staged.copy(mesh->resolved_path, limits.max_file_bytes, error))
          mesh->uri = *relative;
        else
          report_rule(sink, "export-write", mesh->uri_source,
                      "cannot copy the mesh '" + mesh->resolved_path + "': " + error);
      }
}

// --mass-from-geometry: a URDF link without <inertial> has no mass, and simulators refuse a
// moving massless link; its shapes at `density` give it one, reported at the link as a change.
void mass_from_geometry(bodyfmt::Model& model, double density, bodyfmt::DiagnosticSink& sink) {
  using namespace bodyfmt;
  for (Link& link : model.links) {
    // The importer's mark of a link without <inertial>: one massless contribution at the link.
    if (link.mass_contributions.size() != 1 || link.sources.mass().known()) continue;
    MassContribution& c = link.mass_contributions.front();
    if (!c.from_link_keys || c.mass != 0 || c.source != link.source) continue;
    // The importer resolves mesh files without reading them; their triangles are needed here.
    for (Shape& shape : link.shapes) {
      auto* resource = geometry_if<MeshResource>(shape.geometry);
      if (!resource || resource->resolved_path.empty() || resource->mesh >= 0) continue;
      MeshImportOptions options;
      options.length_scale = resource->length_scale;
      options.y_up = resource->y_up;
      options.node = resource->node;
      if (auto asset = import_mesh(resource->resolved_path, options, sink, resource->uri_source)) {
        resource->mesh = static_cast<MeshIndex>(model.meshes.size());
        model.meshes.push_back(std::move(*asset));
      }
    }
    const LinkGeometryMass geometry = link_geometry_mass(model, link, sink);
    const std::optional<MassProperties> m = link_mass_from_geometry(link, geometry, density);
    if (!m) continue;
    c.mass = m->mass;
    c.center_of_mass = m->center_of_mass;
    c.inertia = m->inertia;
    const Eigen::Matrix3d& I = m->inertia;
    report_rule(sink, "export-value-changed", link.source,
                fmt::format("link \"{}\" has no <inertial> (mass 0 in URDF): mass 0 -> {:.6g} kg, centre of mass "
                            "[{:.6g}, {:.6g}, {:.6g}], inertia [{:.6g}, {:.6g}, {:.6g}, {:.6g}, {:.6g}, {:.6g}] from "
                            "its {} shapes at {:g} kg/m³",
                            link.name, m->mass, m->center_of_mass.x(), m->center_of_mass.y(), m->center_of_mass.z(),
                            I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2),
                            geometry.from_visual ? "visual" : "collision", density));
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bodyfmt;
  tools::Front front("urdf2body", "Import a URDF robot model as a Choreonoid .body file (format 2.0)", {false, true});
  std::string output;
  CLI::App& app = front.app();
  app.add_option("-o,--output", output, "the .body file to write ('-': standard output)")->required();
  bool copy_meshes = false;
  app.add_flag("--copy-meshes", copy_meshes,
               "copy the mesh files into meshes/STEM/ beside the .body (STEM: the output's file stem) and refer to "
               "the copies");
  double density = 0;
  app.add_option("--mass-from-geometry", density,
                 "give each link without <inertial> the mass properties of its collision shapes (visual where it has "
                 "none) at DENSITY kg/m³, reported as a value change")
      ->type_name("DENSITY")
      ->check(tools::number_above_zero(false));
  if (CLI::Option* file = app.get_option_no_throw("file")) file->description("the URDF file, or - for standard input");
  if (auto code = front.parse(argc, argv)) return *code;

  const std::string& path = front.inputs().front();
  std::string urdf_name;  // as locations name it: the file, or --stdin-filename
  tools::ExportSteps steps;
  steps.read = [&](const tools::ModelInput& input, DiagnosticSink& sink) -> std::optional<Model> {
    auto text = read_text(input, front.load_options().max_file_bytes, sink);
    if (!text) return std::nullopt;
    urdf_name = input.name;
    // The file asked for: its findings quote it (a load does this for a .body).
    if (front.load_options().on_model_text) front.load_options().on_model_text(input.name);
    urdf_import::UrdfImportOptions options;
    options.package_paths = front.load_options().package_paths;
    options.use_ros_package_path = front.load_options().use_ros_package_path;
    options.resolve_meshes = front.load_options().load_meshes;
    options.confine_meshes = copy_meshes;
    const fs::path given = output == "-" ? fs::path() : fs::path(output).parent_path();
    options.output_folder = given.empty() ? fs::path(".") : given;
    auto model = urdf_import::import_urdf(*text, input.name, options, sink);
    if (model && density > 0) mass_from_geometry(*model, density, sink);
    return model;
  };
  steps.stage = [&](Model& model, converters::OutputSet& out, DiagnosticSink& sink) {
    BodyWriteOptions write_options;
    write_options.comment = "generated by urdf2body from " + fs::path(urdf_name).filename().string();
    // The run protects every mesh the URDF names (also without --copy-meshes); the URDF is
    // not one of the model's input files.
    if (path != "-") out.protect(path, "the URDF");
    if (copy_meshes) copy_mesh_files(model, out, front.load_options(), sink);
    out.set_main(write_body(model, write_options, sink));
    return true;
  };
  steps.refusal = [&](const std::vector<Diagnostic>& diagnostics) {
    const bool strict_losses = std::any_of(diagnostics.begin(), diagnostics.end(), [](const Diagnostic& d) {
      return (d.rule_id == "export-loss" || d.rule_id == "export-value-changed") && d.severity >= Severity::kError;
    });
    if (strict_losses) return std::string("--strict makes every loss and every changed value an error");
    return front.may_write(diagnostics) ? std::string()
                                        : std::string("the URDF has errors (--best-effort writes it anyway)");
  };
  return tools::run_export(front, output, steps);
}
