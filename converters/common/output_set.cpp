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
  assert(!relative.empty() && relative.find("..") == std::string::npos);
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
  for (std::size_t i = 0; i < staged.size(); ++i) {
    fs::rename(staged[i].temp, staged[i].target, ec);
    if (ec) {
      // Files renamed so far stay (a rename cannot be undone without the old contents);
      // the rest are removed.
      report_write(sink, staged[i].target, ec.message());
      std::error_code ignored;
      for (std::size_t j = i; j < staged.size(); ++j) fs::remove(staged[j].temp, ignored);
      failed_ = true;
      return false;
    }
  }
  return true;
}

}  // namespace bodyfmt::converters
