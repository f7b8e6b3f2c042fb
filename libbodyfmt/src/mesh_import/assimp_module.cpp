#include "mesh_import/assimp_module.h"

#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include "mesh_import/assimp_reader.h"  // the entry point's declaration, for its type
#include "mesh_import/vrml_reader.h"    // resolve_relative, passed to the module

#include <dlfcn.h>

#include <mutex>
#include <vector>

namespace bodyfmt::mesh {

namespace {

// The module's file name; libbodyfmt/CMakeLists.txt sets the same name on the module target.
constexpr const char* kModuleName = "libbodyfmt_assimp.so";
constexpr const char* kAssimpEntryPoint = "bodyfmt_assimp_read_v3";

using EntryPoint = decltype(&bodyfmt_assimp_read_v3);

const AssimpHost kHost = {
    [](DiagnosticSink& sink, const char* rule_id, const SourceLocation& where, std::string message) {
      report_rule(sink, rule_id, where, std::move(message));
    },
    &resolve_relative,
    &read_regular_file_bytes,
};

struct Module {
  EntryPoint read = nullptr;
  std::string path;   // the path tried
  std::string error;  // why it could not be loaded, when read is null
};

/// The directory of the file that holds libbodyfmt's code: libbodyfmt.so, or the executable that
/// links libbodyfmt statically (the project's tools).
std::string code_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&import_with_assimp), &info) == 0 || !info.dli_fname) return {};
  const std::string file = info.dli_fname;
  const auto slash = file.rfind('/');
  return slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
}

/// Where the module may be, most likely first. It is built and installed next to libbodyfmt.so,
/// so it is found without LD_LIBRARY_PATH or an RPATH: beside libbodyfmt.so; for an installed
/// tool, in the library folder relative to the tool's (BODYFMT_MODULE_FROM_BINDIR, "../lib/");
/// for an executable of the build tree that links libbodyfmt statically (tools, tests), in
/// the build folder of the module (BODYFMT_MODULE_BUILD_DIR).
std::vector<std::string> candidate_paths() {
  const std::string here = code_directory();
  std::vector<std::string> paths{here + kModuleName};
#ifdef BODYFMT_MODULE_FROM_BINDIR
  if (!here.empty()) paths.push_back(here + BODYFMT_MODULE_FROM_BINDIR + kModuleName);
#endif
#ifdef BODYFMT_MODULE_BUILD_DIR
  paths.push_back(std::string(BODYFMT_MODULE_BUILD_DIR) + kModuleName);
#endif
  return paths;
}

Module load_module() {
  Module module;
  // RTLD_LOCAL: assimp's symbols stay out of the global namespace of the host program.
  // The handle is never closed: the scene trees are allocated by the module (make_shared),
  // so their control blocks' code lives there and must outlive every cached tree.
  void* handle = nullptr;
  for (const std::string& path : candidate_paths()) {
    handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle) {
      module.path = path;
      break;
    }
    // Reported when none loads: the first place, where the module belongs.
    if (module.path.empty()) {
      const char* error = dlerror();
      module.path = path;
      module.error = error ? error : "dlopen failed";
    }
  }
  if (!handle) return module;
  module.error.clear();
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

SceneTree import_with_assimp(const std::string& path, std::uintmax_t max_file_bytes, DiagnosticSink& sink,
                             const SourceLocation& where) {
  const Module& m = module();
  if (!m.read) {
    report_rule(
        sink, "mesh-importer-unavailable", where,
        "cannot import \"" + path + "\": the mesh importer module \"" + m.path + "\" could not be loaded: " + m.error,
        std::string("install ") + kModuleName + " next to libbodyfmt (it is part of the bodyfmt build)");
    return nullptr;
  }
  SceneTree tree;
  m.read(&kHost, path.c_str(), max_file_bytes, &sink, &where, &tree);
  return tree;
}

}  // namespace bodyfmt::mesh
