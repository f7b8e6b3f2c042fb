#include "mesh/assimp_module.h"

#include <bodyfmt/rules.h>
#include "mesh/assimp_reader.h"  // the entry point's declaration, for its type

#include <dlfcn.h>

#include <mutex>

namespace bodyfmt::mesh {

namespace {

// The module's file name; libbodyfmt/CMakeLists.txt sets the same name on the module target.
constexpr const char* kModuleName = "libbodyfmt_assimp.so";
constexpr const char* kAssimpEntryPoint = "bodyfmt_assimp_read_v1";

using EntryPoint = decltype(&bodyfmt_assimp_read_v1);

struct Module {
  EntryPoint read = nullptr;
  std::string path;   // the path tried
  std::string error;  // why it could not be loaded, when read is null
};

/// The directory of the file that holds libbodyfmt itself: the module is installed (and built)
/// next to it, so it is found without LD_LIBRARY_PATH or an RPATH in every executable.
std::string library_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&import_with_assimp), &info) == 0 || !info.dli_fname) return {};
  const std::string file = info.dli_fname;
  const auto slash = file.rfind('/');
  return slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
}

Module load_module() {
  Module module;
  module.path = library_directory() + kModuleName;
  // RTLD_LOCAL: assimp's symbols stay out of the global namespace of the host program.
  // The handle is never closed: the scene trees are allocated by the module (make_shared),
  // so their control blocks' code lives there and must outlive every cached tree.
  void* handle = dlopen(module.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* error = dlerror();
    module.error = error ? error : "dlopen failed";
    return module;
  }
  dlerror();  // clear, so that a null result below is told apart from a null symbol
  void* symbol = dlsym(handle, kAssimpEntryPoint);
  if (!symbol) {
    const char* error = dlerror();
    module.error = error ? error : std::string(kAssimpEntryPoint) + " is null";
    return module;
  }
  module.read = reinterpret_cast<EntryPoint>(symbol);
  return module;
}

const Module& module() {
  static std::once_flag once;
  static Module loaded;
  std::call_once(once, [] { loaded = load_module(); });
  return loaded;
}

}  // namespace

SceneTree import_with_assimp(const std::string& path, DiagnosticSink& sink, const SourceLocation& where) {
  const Module& m = module();
  if (!m.read) {
    report_rule(
        sink, "mesh-importer-unavailable", where,
        "cannot import \"" + path + "\": the mesh importer module \"" + m.path + "\" could not be loaded: " + m.error,
        std::string("install ") + kModuleName + " next to libbodyfmt (it is part of the bodyfmt build)");
    return nullptr;
  }
  SceneTree tree;
  m.read(path.c_str(), &sink, &where, &tree);
  return tree;
}

}  // namespace bodyfmt::mesh
