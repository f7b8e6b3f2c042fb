#pragma once
/// Atomic, all-or-nothing output of one export (main file, meshes, copied resources).
///
/// Files are staged in memory with add() and written by commit(). Before anything is written,
/// commit() looks at what is at each destination:
/// - an input of the run (protect(): the model, its SubBody files, its meshes) is never
///   written; the whole commit is refused;
/// - a symbolic link is written through: its final target gets the new contents, the link stays;
/// - a device, FIFO or socket (`/dev/stdout`, `/dev/null`, a named pipe) is written directly,
///   never renamed over; a folder is refused;
/// - a generated file in a subfolder (a mesh) that exists with other bytes is replaced only when
///   the folder's `.bodyfmt-export` record says this export wrote it, so two exports sharing a
///   mesh folder never overwrite each other's files silently;
/// - a file the record gives to this export that it no longer writes (renamed, removed, in
///   another format) is stale and removed after the commit; the record is the only evidence
///   taken, so a file it does not list is never removed.
/// Regular files then go to a temporary file beside their destination, and only when every
/// temporary file has been written are they renamed over their destinations, the main file last,
/// each existing destination kept under a hard link first. A failure at any point removes the
/// temporary files and puts every replaced destination back, so an existing output stays as it
/// was and no partial file is left. Concurrent exports to one destination each write a whole
/// file; the last one wins. A main path of "-" writes the main file to standard output, last.
/// After fail() (a fatal diagnostic during the export) commit() writes nothing.
#include <bodyfmt/diagnostic.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bodyfmt::converters {

class OutputSet {
 public:
  /// `main_path` is the main output file ("-": standard output); other files are placed
  /// relative to its folder (the current folder for standard output).
  explicit OutputSet(std::filesystem::path main_path);

  const std::filesystem::path& main_path() const { return main_path_; }
  bool to_stdout() const { return main_path_ == "-"; }
  /// The folder of the main file (where relative URIs start).
  std::filesystem::path directory() const;

  /// `path` is an input of the run (`what`: "the model", "a mesh", ...): commit() refuses to
  /// write over it, however the path is spelled (links, "..", hard links).
  void protect(const std::string& path, std::string what);

  /// Lets staged paths climb out of the output folder with ".." as far as `root` (a ROS
  /// package's folder), and no further.
  void allow_root(std::filesystem::path root) { root_ = std::move(root); }

  /// Stages `contents` for `relative` (relative to directory(), '/'-separated). A path that
  /// is absolute or climbs out with ".." would write outside the output folder (or the root
  /// of allow_root()): commit() then reports it and writes nothing (writers make names with
  /// StagedFiles and file_stem).
  void add(const std::string& relative, std::string contents);
  /// Stages the main file.
  void set_main(std::string contents);
  bool has(const std::string& relative) const { return files_.count(relative) != 0; }
  /// Staged files, sorted by relative path (the main file under its file name).
  const std::map<std::string, std::string>& files() const { return files_; }

  /// Marks the export failed: commit() will write nothing.
  void fail() { failed_ = true; }
  bool failed() const { return failed_; }

  /// Writes every staged file (see above). Reports `export-write` (fatal) with the path and
  /// the reason on failure and returns false; returns false without a report after fail().
  bool commit(DiagnosticSink& sink);

  /// The record of which export wrote each generated file of a folder.
  static constexpr const char* kRecordName = ".bodyfmt-export";

 private:
  std::string main_key() const;

  std::filesystem::path main_path_;
  std::map<std::string, std::string> files_;
  std::vector<std::pair<std::string, std::string>> protected_;  ///< path, what
  std::filesystem::path root_;                                  ///< see allow_root(); empty: the output folder
  std::string outside_;                                         ///< the first staged path that leaves the output folder
  bool failed_ = false;
};

}  // namespace bodyfmt::converters
