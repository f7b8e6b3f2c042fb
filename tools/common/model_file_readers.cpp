#include "model_file_readers.h"

#include "urdf_reader.h"

#include <filesystem>

namespace bodyfmt::tools {

void add_model_file_readers(LoadOptions& options) {
  options.model_file_readers[".urdf"] = [](const std::string& path, const std::string& text, const LoadOptions& load,
                                           DiagnosticSink& sink) {
    urdf_import::UrdfImportOptions import;
    // A wrapper is a Body file: it loads as Choreonoid's URDF loader loads the URDF.
    import.semantics = urdf_import::UrdfSemantics::kChoreonoid;
    import.package_paths = load.package_paths;
    import.use_ros_package_path = load.use_ros_package_path;
    import.resolve_meshes = load.load_meshes;
    // Mesh URIs as a .body beside the URDF would write them; the loaded model's meshes are
    // read through their resolved paths.
    import.output_folder = std::filesystem::path(path).parent_path();
    std::optional<Model> model = urdf_import::import_urdf(text, path, import, sink);
    // Read as URDF: its findings may quote it. A file that gives no model is not quoted.
    if (model && load.on_model_text) load.on_model_text(path);
    // Choreonoid names a joint after its link unless it has a name of its own; a loaded .body
    // (urdf2body's output) says so with an empty joint_name, and so does this model.
    if (model)
      for (Link& link : model->links)
        if (link.joint_name == link.name) link.joint_name = HeapString();
    return model;
  };
}

}  // namespace bodyfmt::tools
