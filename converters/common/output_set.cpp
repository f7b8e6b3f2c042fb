#include <bodyfmt/converters/output_set.h>

#include <bodyfmt/rules.h>
#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cassert>
#include <fstream>
#include <system_error>
#include <utility>
#include <vector>

namespace bodyfmt::converters {

namespace fs = std::filesystem;

OutputSet::OutputSet(fs::path main_path) : main_path_(std::move(main_path)) {}

fs::path OutputSet::directory() const {
  fs::path dir = main_path_.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

void OutputSet::add(const std::string& relative, std::string contents) {
  const fs::path path(relative);
  bool inside = !relative.empty() && path.is_relative();
  for (const fs::path& part : path) inside = inside && part != "..";
  if (!inside) {
    if (outside_.empty()) outside_ = relative;
    return;
  }
  files_[relative] = std::move(contents);
}

void OutputSet::set_main(std::string contents) { files_[main_path_.filename().string()] = std::move(contents); }

namespace {

struct Staged {
  fs::path temp;
  fs::path target;
};

void report_write(DiagnosticSink& sink, const fs::path& path, const std::string& why) {
  report_rule(sink, "export-write", SourceLocation{path.string(), 0, 0},
              fmt::format("cannot write '{}': {}", path.string(), why));
}

}  // namespace

bool OutputSet::commit(DiagnosticSink& sink) {
  if (!outside_.empty()) {
    report_write(sink, directory() / outside_, "the path leaves the output folder; nothing is written");
    failed_ = true;
  }
  if (failed_) return false;
  const fs::path dir = directory();
  std::vector<Staged> staged;
  std::vector<fs::path> created_dirs;
  std::error_code ec;

  auto roll_back = [&] {
    std::error_code ignored;
    for (const Staged& s : staged) fs::remove(s.temp, ignored);
    // Remove the folders this commit created, innermost first, if they are empty.
    for (auto it = created_dirs.rbegin(); it != created_dirs.rend(); ++it) {
      if (fs::is_empty(*it, ignored)) fs::remove(*it, ignored);
    }
    failed_ = true;
  };

  // The process id and a counter keep concurrent exports into one folder apart.
  int counter = 0;
  for (const auto& [relative, contents] : files_) {
    const fs::path target = dir / fs::path(relative);
    const fs::path parent = target.parent_path();
    if (!fs::is_directory(parent, ec)) {
      // Record each folder level that does not exist yet, outermost first.
      std::vector<fs::path> missing;
      for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.insert(missing.begin(), p);
        if (p == p.parent_path()) break;
      }
      if (!fs::create_directories(parent, ec) && ec) {
        report_write(sink, target, ec.message());
        roll_back();
        return false;
      }
      created_dirs.insert(created_dirs.end(), missing.begin(), missing.end());
    }
    const fs::path temp =
        parent / fmt::format(".{}.tmp-{}-{}", target.filename().string(), static_cast<long>(::getpid()), counter++);
    staged.push_back({temp, target});
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) {
      report_write(sink, target, "the temporary file could not be written");
      roll_back();
      return false;
    }
  }
  // The main file goes last: if a rename fails, no new main file refers to missing parts.
  std::stable_partition(staged.begin(), staged.end(), [&](const Staged& s) {
    return s.target.filename() != main_path_.filename() || s.target.parent_path() != dir;
  });
  // Each existing target is first kept under a hard link (a copy where the file system has no
  // links); the rename then replaces it in one step, so a reader or a concurrent export never
  // sees the destination missing. If any rename fails, every target renamed so far gets its old
  // file back, so a failed commit leaves the earlier output exactly as it was.
  std::vector<std::pair<fs::path, fs::path>> moved_aside;  // backup, target
  std::vector<fs::path> placed;
  auto undo = [&] {
    std::error_code ignored;
    for (const fs::path& target : placed) fs::remove(target, ignored);
    for (const auto& [backup, target] : moved_aside) fs::rename(backup, target, ignored);
    for (const Staged& s : staged) fs::remove(s.temp, ignored);
    failed_ = true;
  };
  for (std::size_t i = 0; i < staged.size(); ++i) {
    const Staged& s = staged[i];
    if (fs::is_regular_file(s.target, ec)) {
      const fs::path backup = s.target.parent_path() / fmt::format(".{}.old-{}-{}", s.target.filename().string(),
                                                                   static_cast<long>(::getpid()), i);
      fs::create_hard_link(s.target, backup, ec);
      if (ec && ec != std::errc::no_such_file_or_directory) {
        ec.clear();
        fs::copy_file(s.target, backup, ec);
      }
      // A destination that vanished meanwhile (a concurrent export moving it) needs no backup.
      if (ec && ec != std::errc::no_such_file_or_directory) {
        report_write(sink, s.target, ec.message());
        undo();
        return false;
      }
      if (!ec) moved_aside.emplace_back(backup, s.target);
    }
    fs::rename(s.temp, s.target, ec);
    if (ec) {
      report_write(sink, s.target, ec.message());
      undo();
      return false;
    }
    placed.push_back(s.target);
  }
  std::error_code ignored;
  for (const auto& [backup, target] : moved_aside) fs::remove(backup, ignored);
  return true;
}

}  // namespace bodyfmt::converters
