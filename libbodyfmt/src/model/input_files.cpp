#include <bodyfmt/input_files.h>

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <set>

namespace bodyfmt {

namespace {
std::atomic<bool> standard_input_read{false};
}  // namespace

void note_standard_input_read() { standard_input_read = true; }

std::vector<InputFile> input_files(const Model& model) {
  // Each location's file name is interned, so the set of model files stays small however many
  // elements a model has.
  std::set<std::string> body_files{model.source_file};
  std::set<std::string> meshes;
  std::set<std::string> textures;
  auto texture = [&](const std::optional<Texture>& t) {
    if (t && !t->resolved_path.empty()) textures.insert(t->resolved_path);
  };
  body_files.insert(model.source.file.str());
  for (const Link& link : model.links) {
    body_files.insert(link.source.file.str());
    for (const Shape& shape : link.shapes) {
      body_files.insert(shape.source.file.str());
      texture(shape.appearance.texture);
      if (const auto* resource = geometry_if<MeshResource>(shape.geometry);
          resource && !resource->resolved_path.empty())
        meshes.insert(resource->resolved_path);
    }
  }
  for (const Device& device : model.devices) body_files.insert(device.source.file.str());
  for (const ExtraJoint& joint : model.extra_joints) body_files.insert(joint.source.file.str());
  for (const MeshAsset& asset : model.meshes) {
    meshes.insert(asset.path);
    for (const MeshPart& part : asset.parts) texture(part.texture);
  }
  std::vector<InputFile> files;
  for (const std::string& file : body_files)
    if (!file.empty()) files.push_back({file, file == model.source_file ? "the model" : "a model file it includes"});
  for (const std::string& file : meshes)
    if (!file.empty()) files.push_back({file, "a mesh of the model"});
  for (const std::string& file : textures)
    if (!file.empty()) files.push_back({file, "a texture of the model"});
  struct stat st {};
  if (standard_input_read && ::fstat(STDIN_FILENO, &st) == 0 && S_ISREG(st.st_mode))
    files.push_back({"/dev/stdin", "the model's file, read from standard input"});
  return files;
}

}  // namespace bodyfmt
