#include <bodyfmt/converters/output_set.h>

#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

namespace bodyfmt::converters {

namespace fs = std::filesystem;

OutputSet::OutputSet(fs::path main_path) : main_path_(std::move(main_path)) {}

fs::path OutputSet::directory() const {
  if (to_stdout()) return ".";
  fs::path dir = main_path_.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

void OutputSet::protect(const std::string& path, std::string what) {
  if (!path.empty()) protected_.emplace_back(path, std::move(what));
}

void OutputSet::add(const std::string& relative, std::string contents) {
  const fs::path path(relative);
  bool inside = !relative.empty() && path.is_relative();
  bool climbs = false;
  for (const fs::path& part : path) climbs = climbs || part == "..";
  if (inside && climbs) {
    std::error_code ec;
    const fs::path within =
        (fs::absolute(directory(), ec) / path).lexically_normal().lexically_relative(root_.lexically_normal());
    inside = !root_.empty() && !within.empty() && *within.begin() != "..";
  }
  if (!inside) {
    if (outside_.empty()) outside_ = relative;
    return;
  }
  files_[relative] = std::move(contents);
}

std::string OutputSet::main_key() const { return to_stdout() ? std::string("-") : main_path_.filename().string(); }

void OutputSet::set_main(std::string contents) { files_[main_key()] = std::move(contents); }

namespace {

void report_write(DiagnosticSink& sink, const fs::path& path, const std::string& why) {
  report_rule(sink, "export-write", SourceLocation{path.string(), 0, 0},
              fmt::format("cannot write '{}': {}", path.string(), why));
}

/// The file a path finally names, following symbolic links (also dangling ones) but not
/// resolving anything else, so that a link is written through rather than replaced.
fs::path follow_links(fs::path path) {
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(path, ec); ++hops) {
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) break;
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  return path.lexically_normal();
}

// A folder's record is a line per generated file; far more than any export writes.
constexpr std::uintmax_t kMaxRecordBytes = 16u << 20;

/// The regular file at `path` up to `max_bytes`, through the one bounded reader: nothing for a
/// FIFO or a device put in the output folder (which a plain stream would block on), a missing
/// file, or one larger than the limit.
std::optional<std::string> read_bounded(const fs::path& path, std::uintmax_t max_bytes) {
  std::string why;
  return read_regular_file(path.string(), max_bytes, why);
}

/// A folder's record of generated files: file name -> the export (its main file, relative to
/// the folder) that wrote it. One "name<TAB>owner" line per file, sorted.
using Record = std::map<std::string, std::string>;

Record read_record(const fs::path& folder) {
  Record record;
  // An unreadable record claims nothing: every file there is then one this export did not write.
  std::istringstream in(read_bounded(folder / OutputSet::kRecordName, kMaxRecordBytes).value_or(""));
  std::string line;
  while (std::getline(in, line)) {
    const auto tab = line.find('\t');
    if (tab != std::string::npos) record[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return record;
}

std::string format_record(const Record& record) {
  std::string text;
  for (const auto& [name, owner] : record) text += name + '\t' + owner + '\n';
  return text;
}

/// Why a generated file (a mesh, a texture, a .bin, a folder's record) must not be written at
/// `relative` below `dir`: the tool chose every name on that path, so a symbolic link there
/// (the file, or a folder on the way) was planted, and a device or FIFO would block or swallow
/// the file. Sets `where` to the offending path; empty when the file may be written.
std::string generated_path_problem(const fs::path& dir, const fs::path& relative, fs::path& where) {
  fs::path path = dir;
  std::error_code ec;
  for (auto part = relative.begin(); part != relative.end(); ++part) {
    path /= *part;
    if (*part == ".." || *part == ".") continue;  // climbing to a package root the user named
    const fs::file_status status = fs::symlink_status(path, ec);
    if (!fs::exists(status)) return {};  // created by this export from here on
    where = path;
    if (fs::is_symlink(status))
      return "it is a symbolic link, and the tool never follows one where it chooses the names (a generated "
             "file or its folder); remove the link";
    if (std::next(part) == relative.end() && !fs::is_regular_file(status))
      return "it is not a regular file (generated files are replaced whole); remove it";
  }
  return {};
}

/// One file to write: where the writer put it, where it really goes, and how.
struct Destination {
  std::string relative;  ///< key in files_
  fs::path given;        ///< as the writer named it (below directory())
  fs::path target;       ///< after following symbolic links
  bool direct = false;   ///< a device, FIFO or socket: written in place
  bool unchanged = false;
  fs::path temp;
};

bool write_direct(const fs::path& path, const std::string& contents) {
  std::ofstream out(path, std::ios::binary);
  out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
  out.close();
  return static_cast<bool>(out);
}

/// One commit of an OutputSet, in its phases (output_set.h): plan() looks at every destination
/// and refuses before anything is written; write_temporaries() puts each new file beside its
/// destination; replace_destinations() renames them over their destinations and writes devices
/// and standard output, undoing every step when one fails; clean_up() removes the backups and
/// the stale files. A phase that fails has reported why and returns false.
class Commit {
 public:
  Commit(const fs::path& main_path, const fs::path& dir, bool to_stdout, std::string main,
         std::map<std::string, std::string>& files,
         const std::vector<std::pair<std::string, std::string>>& protected_paths, DiagnosticSink& sink)
      : main_path_(main_path),
        dir_(dir),
        to_stdout_(to_stdout),
        main_(std::move(main)),
        files_(files),
        protected_(protected_paths),
        sink_(sink) {}

  bool plan() { return plan_files() && plan_records(); }
  bool write_temporaries();
  bool replace_destinations();
  void clean_up();

 private:
  bool refuse(const fs::path& path, const std::string& why) {
    report_write(sink_, path, why + "; nothing was written");
    return false;
  }
  /// What is at each destination decides how it is written, or whether anything is.
  bool plan_files();
  /// A generated file in a subfolder belongs to the export that wrote it: claims `d` in its
  /// folder's record, or refuses a file of that name that another export (or the user) wrote.
  bool claim(Destination& d, const std::string& contents, bool exists);
  /// The main file, as the record of `folder` names its owner.
  std::string self_in(const fs::path& folder) const;
  /// The stale files, and each updated record as a destination of its own.
  bool plan_records();
  void remove_temps();
  /// Removes the temporary files and the folders this commit created.
  void roll_back();
  /// Puts every replaced destination back, then rolls back.
  void undo();

  const fs::path& main_path_;
  const fs::path dir_;
  const bool to_stdout_;
  const std::string main_;
  std::map<std::string, std::string>& files_;
  const std::vector<std::pair<std::string, std::string>>& protected_;
  DiagnosticSink& sink_;

  std::vector<Destination> destinations_;
  std::map<fs::path, Record> records_;                      // subfolder -> its updated record
  std::map<fs::path, std::set<std::string>> staged_names_;  // subfolder -> the names this commit writes there
  std::vector<fs::path> stale_;
  std::vector<fs::path> created_dirs_;
  std::vector<std::pair<fs::path, fs::path>> kept_;  // backup, target
  std::vector<fs::path> placed_;
};

bool Commit::plan_files() {
  std::error_code ec;
  for (auto& [relative, contents] : files_) {
    const bool is_main = relative == main_;
    if (is_main && to_stdout_) continue;
    Destination d;
    d.relative = relative;
    d.given = is_main ? main_path_ : dir_ / fs::path(relative);
    if (!is_main) {
      fs::path where;
      const std::string problem = generated_path_problem(dir_, fs::path(relative), where);
      if (!problem.empty()) return refuse(where, problem);
    }
    // The user named the main file: a link there is written through. Generated files never are.
    d.target = is_main ? follow_links(d.given) : d.given.lexically_normal();
    const fs::file_status status = fs::status(d.target, ec);
    if (fs::is_directory(status)) return refuse(d.given, "it is a folder");
    const bool exists = fs::exists(status);
    d.direct = exists && !fs::is_regular_file(status);
    if (exists) {
      for (const auto& [input, what] : protected_) {
        if (fs::equivalent(d.target, input, ec) && !ec)
          return refuse(d.given, fmt::format("it is {} of this run ('{}')", what, input));
      }
    }
    if (!is_main && fs::path(relative).has_parent_path() && !d.direct && !claim(d, contents, exists)) return false;
    destinations_.push_back(std::move(d));
  }
  return true;
}

std::string Commit::self_in(const fs::path& folder) const {
  std::error_code ec;
  return to_stdout_ ? std::string("-")
                    : fs::absolute(main_path_, ec).lexically_relative(fs::absolute(folder, ec)).generic_string();
}

bool Commit::claim(Destination& d, const std::string& contents, bool exists) {
  std::error_code ec;
  const fs::path folder = d.given.parent_path();
  auto [it, fresh] = records_.try_emplace(folder);
  if (fresh) {
    fs::path where;
    const std::string problem =
        generated_path_problem(dir_, fs::path(d.relative).parent_path() / OutputSet::kRecordName, where);
    if (!problem.empty()) return refuse(where, problem);
    if (fs::is_directory(folder, ec)) it->second = read_record(folder);
  }
  Record& record = it->second;
  const std::string name = d.given.filename().string();
  staged_names_[folder].insert(name);
  const std::string self = self_in(folder);
  const auto owner = record.find(name);
  if (exists && read_bounded(d.target, contents.size()) == contents) {
    d.unchanged = true;
  } else if (exists && (owner == record.end() || owner->second != self)) {
    return refuse(d.given, owner == record.end()
                               ? std::string("a file of that name exists that this export did not write "
                                             "(choose another --mesh-folder, or remove the file)")
                               : fmt::format("it was written by the export to '{}' (choose another "
                                             "--mesh-folder or output name, or remove the file)",
                                             (folder / owner->second).lexically_normal().string()));
  }
  if (owner == record.end() || !d.unchanged) record[name] = self;
  return true;
}

bool Commit::plan_records() {
  std::error_code ec;
  // A file the record gives to this export that it no longer writes (a mesh renamed, removed
  // or written in another format since) is stale: removed once the new files are in place. The
  // record is the only evidence taken, so a file it does not list (the user's) is never removed.
  for (auto& [folder, record] : records_) {
    const std::string self = self_in(folder);
    for (auto it = record.begin(); it != record.end();) {
      if (it->second == self && staged_names_[folder].count(it->first) == 0) {
        stale_.push_back(folder / it->first);
        it = record.erase(it);
      } else {
        ++it;
      }
    }
  }
  for (const auto& [folder, record] : records_) {
    Destination d;
    d.relative = (folder.lexically_relative(dir_) / OutputSet::kRecordName).generic_string();
    fs::path where;
    const std::string problem = generated_path_problem(dir_, fs::path(d.relative), where);
    if (!problem.empty()) return refuse(where, problem);
    d.given = d.target = folder / OutputSet::kRecordName;
    files_[d.relative] = format_record(record);
    d.unchanged =
        fs::is_regular_file(d.target, ec) && read_bounded(d.target, files_[d.relative].size()) == files_[d.relative];
    destinations_.push_back(std::move(d));
  }
  return true;
}

void Commit::remove_temps() {
  std::error_code ignored;
  for (const Destination& d : destinations_)
    if (!d.temp.empty()) fs::remove(d.temp, ignored);
}

void Commit::roll_back() {
  std::error_code ignored;
  remove_temps();
  // Remove the folders this commit created, innermost first, if they are empty.
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
    if (fs::is_empty(*it, ignored)) fs::remove(*it, ignored);
  }
}

bool Commit::write_temporaries() {
  std::error_code ec;
  // The process id and a counter keep concurrent exports into one folder apart.
  int counter = 0;
  for (Destination& d : destinations_) {
    if (d.direct || d.unchanged) continue;
    const fs::path parent = d.target.parent_path().empty() ? fs::path(".") : d.target.parent_path();
    if (!fs::is_directory(parent, ec)) {
      // Record each folder level that does not exist yet, outermost first.
      std::vector<fs::path> missing;
      for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.insert(missing.begin(), p);
        if (p == p.parent_path()) break;
      }
      if (!fs::create_directories(parent, ec) && ec) {
        report_write(sink_, d.given, ec.message());
        roll_back();
        return false;
      }
      created_dirs_.insert(created_dirs_.end(), missing.begin(), missing.end());
    }
    d.temp =
        parent / fmt::format(".{}.tmp-{}-{}", d.target.filename().string(), static_cast<long>(::getpid()), counter++);
    if (!write_direct(d.temp, files_[d.relative])) {
      report_write(sink_, d.given, "the temporary file could not be written");
      roll_back();
      return false;
    }
  }
  return true;
}

void Commit::undo() {
  std::error_code ignored;
  for (const fs::path& target : placed_) fs::remove(target, ignored);
  for (const auto& [backup, target] : kept_) fs::rename(backup, target, ignored);
  roll_back();  // the temporary files, and the folders this commit created
}

bool Commit::replace_destinations() {
  std::error_code ec;
  // The main file goes last: if a rename fails, no new main file refers to missing parts.
  std::stable_partition(destinations_.begin(), destinations_.end(),
                        [&](const Destination& d) { return d.relative != main_; });
  // Each existing target is first kept under a hard link (a copy where the file system has no
  // links); the rename then replaces it in one step, so a reader or a concurrent export never
  // sees the destination missing. If any step fails, every target replaced so far gets its old
  // file back, so a failed commit leaves the earlier output exactly as it was.
  for (std::size_t i = 0; i < destinations_.size(); ++i) {
    const Destination& d = destinations_[i];
    if (d.unchanged || d.direct) continue;
    if (fs::is_regular_file(d.target, ec)) {
      const fs::path backup = d.target.parent_path() / fmt::format(".{}.old-{}-{}", d.target.filename().string(),
                                                                   static_cast<long>(::getpid()), i);
      fs::create_hard_link(d.target, backup, ec);
      if (ec && ec != std::errc::no_such_file_or_directory) {
        ec.clear();
        fs::copy_file(d.target, backup, ec);
      }
      // A destination that vanished meanwhile (a concurrent export moving it) needs no backup.
      if (ec && ec != std::errc::no_such_file_or_directory) {
        report_write(sink_, d.given, ec.message());
        undo();
        return false;
      }
      if (!ec) kept_.emplace_back(backup, d.target);
    }
    fs::rename(d.temp, d.target, ec);
    if (ec) {
      report_write(sink_, d.given, ec.message());
      undo();
      return false;
    }
    placed_.push_back(d.target);
  }
  // Devices and FIFOs cannot be replaced in one step: they are written in place, last.
  for (const Destination& d : destinations_) {
    if (d.direct && !write_direct(d.target, files_[d.relative])) {
      report_write(sink_, d.given, "writing to it failed");
      undo();
      return false;
    }
  }
  if (to_stdout_) {
    const std::string& contents = files_[main_];
    std::cout.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    std::cout.flush();
    if (!std::cout) {
      report_write(sink_, "-", "writing to standard output failed");
      undo();
      return false;
    }
  }
  return true;
}

void Commit::clean_up() {
  std::error_code ignored;
  for (const auto& [backup, target] : kept_) fs::remove(backup, ignored);
  for (const fs::path& path : stale_)
    if (fs::is_regular_file(fs::symlink_status(path, ignored))) fs::remove(path, ignored);
}

}  // namespace

bool OutputSet::commit(DiagnosticSink& sink) {
  if (!outside_.empty()) {
    report_write(sink, directory() / outside_, "the path leaves the output folder; nothing is written");
    failed_ = true;
  }
  if (failed_) return false;
  if (main_path_.empty()) {
    report_write(sink, main_path_, "the output path is empty; nothing was written");
    failed_ = true;
    return false;
  }
  Commit commit(main_path_, directory(), to_stdout(), main_key(), files_, protected_, sink);
  if (!commit.plan() || !commit.write_temporaries() || !commit.replace_destinations()) {
    failed_ = true;
    return false;
  }
  commit.clean_up();
  return true;
}

}  // namespace bodyfmt::converters
