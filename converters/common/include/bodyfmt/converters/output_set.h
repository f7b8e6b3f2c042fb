#pragma once
/// Atomic, all-or-nothing output of one export (main file, meshes, copied resources).
///
/// Files are staged in memory with add() and written by commit(): each goes to a temporary
/// file in its destination folder, and only when every temporary file has been written are
/// they all renamed over their destinations, the main file last, each existing destination
/// kept under a hard link first. A failure at any point removes the temporary files and puts
/// every replaced destination back, so an existing output stays as it was and no partial file
/// is left. Concurrent exports to one destination each write a whole file; the last one wins.
/// After fail() (a fatal diagnostic during the export) commit() writes nothing.
#include <bodyfmt/diagnostic.h>

#include <filesystem>
#include <map>
#include <string>

namespace bodyfmt::converters {

class OutputSet {
 public:
  /// `main_path` is the main output file; other files are placed relative to its folder.
  explicit OutputSet(std::filesystem::path main_path);

  const std::filesystem::path& main_path() const { return main_path_; }
  /// The folder of the main file (where relative URIs start).
  std::filesystem::path directory() const;

  /// Stages `contents` for `relative` (relative to directory(), '/'-separated). A path that
  /// is absolute or climbs out with ".." would write outside the output folder: commit()
  /// then reports it and writes nothing (writers make names with StagedFiles and file_stem).
  void add(const std::string& relative, std::string contents);
  /// Stages the main file.
  void set_main(std::string contents);
  bool has(const std::string& relative) const { return files_.count(relative) != 0; }
  /// Staged files, sorted by relative path (the main file under its file name).
  const std::map<std::string, std::string>& files() const { return files_; }

  /// Marks the export failed: commit() will write nothing.
  void fail() { failed_ = true; }
  bool failed() const { return failed_; }

  /// Writes every staged file atomically (see above). Reports `export-write` (fatal) with the
  /// path and the system's reason on failure and returns false; returns false without a
  /// report after fail().
  bool commit(DiagnosticSink& sink);

 private:
  std::filesystem::path main_path_;
  std::map<std::string, std::string> files_;
  std::string outside_;  ///< the first staged path that leaves the output folder
  bool failed_ = false;
};

}  // namespace bodyfmt::converters
