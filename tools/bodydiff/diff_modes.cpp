#include "diff_modes.h"

#include "change_report.h"
#include "git_show.h"
#include "model_loading.h"

#include <bodyfmt/load.h>

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <sstream>

namespace bodyfmt::tools {

int diff_two_files(const DiffRun& run, const std::vector<std::string>& args) {
  if (args.size() != 2) {
    run.front.print_error(
        fmt::format("expected OLD.body NEW.body, got {} file{}", args.size(), args.size() == 1 ? "" : "s"));
    return kExitFatal;
  }
  if (args[0] == "-" && args[1] == "-") {
    run.front.print_error("only one of the two models can be read from standard input");
    return kExitFatal;
  }
  auto old_model = load_quietly(run.front, args[0], "");
  auto new_model = load_quietly(run.front, args[1], "");
  if (!old_model || !new_model) return kExitFatal;
  const std::vector<ModelChange> changes = diff_models(*old_model, *new_model, run.options);
  if (run.format == "json")
    write_json(std::cout, changes, old_model->source_file, new_model->source_file, run.options.tolerance);
  else
    write_text(std::cout, changes, old_model->source_file, new_model->source_file);
  std::cout.flush();
  if (!std::cout) return kExitFatal;
  return changes.empty() ? kExitClean : kExitFindings;
}

int print_textconv(const DiffRun& run, const std::vector<std::string>& args) {
  if (args.size() != 1) {
    run.front.print_error("--textconv takes one file");
    return kExitFatal;
  }
  auto model = load_quietly(run.front, args[0], "");
  if (!model) return kExitFatal;
  std::cout << canonical_text(*model);
  return kExitClean;
}

int git_diff_driver(const DiffRun& run, const std::vector<std::string>& args) {
  // git passes 7 arguments, or 9 for a rename (then the new path and a similarity header).
  if (args.size() != 7 && args.size() != 9) {
    run.front.print_error(fmt::format("--git takes git's 7 (or 9) arguments, not {}", args.size()));
    return kExitFatal;
  }
  const std::string& path = args[0];
  const std::string& new_path = args.size() == 9 ? args[7] : path;
  const bool old_absent = args[1] == "/dev/null", new_absent = args[4] == "/dev/null";
  std::optional<Model> old_model = old_absent ? Model{} : load_quietly(run.front, args[1], path);
  std::optional<Model> new_model = new_absent ? Model{} : load_quietly(run.front, args[4], new_path);
  if (!old_model || !new_model) return kExitFatal;
  std::vector<ModelChange> changes = diff_models(*old_model, *new_model, run.options);
  name_sides(changes, path);
  if (new_path != path) name_sides(changes, new_path);
  if (changes.empty()) return kExitClean;
  std::cout << fmt::format("bodydiff a/{} b/{}\n", path, new_path);
  if (run.format == "json")
    write_json(std::cout, changes, "a/" + path, "b/" + new_path, run.options.tolerance);
  else
    write_text(std::cout, changes, "a/" + path, "b/" + new_path);
  return kExitClean;
}

int diff_against_git(const DiffRun& run, const std::vector<std::string>& args, std::string git_rev, bool staged) {
  const std::string option = staged ? "--staged" : "--git-rev";
  std::string why;
  if (staged) {
    // Before the first commit there is no HEAD: every staged model is new. Outside a
    // repository, reading the index below fails with git's message.
    if (git_commit_exists("HEAD", why)) git_rev = "HEAD";
  } else if (!git_commit_exists(git_rev, why)) {
    run.front.print_error("--git-rev: " + why);
    return kExitFatal;
  }
  if (args.empty()) {
    run.front.print_error(option + " takes the model files to compare");
    return kExitFatal;
  }
  int code = kExitClean;
  std::vector<std::string> documents;
  for (const std::string& file : args) {
    // git reads paths from the working folder; an absolute one would be taken from the
    // repository's top (and missed there), so it is made relative first.
    std::filesystem::path given(file);
    if (given.is_absolute()) given = given.lexically_relative(std::filesystem::current_path());
    const std::string path = given.lexically_normal().string();
    const std::string old_name = (git_rev.empty() ? std::string("HEAD") : git_rev) + ":" + path;
    auto fail = [&](const std::string& why) {
      run.front.print_error(fmt::format("{}: {}: {}", option, file, why));
      code = kExitFatal;
    };
    if (path.empty() || std::filesystem::is_directory(path)) {
      fail("not a model file (a folder)");
      continue;
    }
    GitFile old_file;
    old_file.absent = true;  // before the first commit, every staged model is new
    if (!git_rev.empty()) old_file = git_show(git_rev, path, run.front.load_options().max_file_bytes);
    if (!old_file.text && !old_file.absent) {
      fail(old_file.why);
      continue;
    }
    std::optional<Model> old_model = Model{};
    if (old_file.text) {
      CollectingSink sink;
      old_model = load_body_string(*old_file.text, path, run.front.load_options(), sink);
      if (!old_model) {
        run.front.print_error(fmt::format("{} cannot be loaded", old_name));
        code = kExitFatal;
        continue;
      }
    }
    std::optional<Model> new_model = Model{};
    if (staged) {
      // The index's text, loaded under the work-tree path so that its meshes and included
      // files resolve there; a file not in the index is deleted.
      const GitFile staged_file = git_show("", path, run.front.load_options().max_file_bytes);
      if (!staged_file.text && !staged_file.absent) {
        fail(staged_file.why);
        continue;
      }
      if (staged_file.text) new_model = load_text_quietly(run.front, *staged_file.text, path);
      if (staged_file.absent && old_file.absent) {
        fail(staged_file.why);  // in neither: mistyped, or never added
        continue;
      }
    } else if (std::filesystem::exists(path)) {
      new_model = load_quietly(run.front, path, "");
    } else if (old_file.absent) {
      fail(old_file.why + ", nor in the working tree");
      continue;
    }
    if (!new_model) {
      code = kExitFatal;
      continue;
    }
    std::vector<ModelChange> changes = diff_models(*old_model, *new_model, run.options);
    name_old_side(changes, path, old_name);
    if (run.format == "json") {
      std::ostringstream doc;
      write_json(doc, changes, old_name, path, run.options.tolerance);
      documents.push_back(doc.str());
    } else {
      write_text(std::cout, changes, old_name, path);
    }
    if (!changes.empty() && code == kExitClean && !staged) code = kExitFindings;
  }
  if (run.format == "json") {
    std::cout << "[\n";
    for (std::size_t i = 0; i < documents.size(); ++i) std::cout << (i ? ",\n" : "") << documents[i];
    std::cout << "]\n";
  }
  return code;
}

}  // namespace bodyfmt::tools
