// bodydiff: what changed between two .body models, compared as loaded models, not as text.
// Exit codes as diff(1): 0 the same within the tolerance, 1 they differ, 2 usage or a model that
// cannot be loaded. --textconv prints a canonical text form for git; --git is git's external
// diff driver (which must exit 0 when files differ, or git stops).

#include "front.h"
#include "git_show.h"
#include "number_options.h"

#include <bodyfmt/model_diff.h>
#include <bodyfmt/read_file.h>
#include <bodyfmt/rules.h>
#include <bodyfmt/text.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {

using namespace bodyfmt;

std::string_view kind_name(ChangeKind kind) {
  switch (kind) {
    case ChangeKind::kAdded: return "added";
    case ChangeKind::kRemoved: return "removed";
    case ChangeKind::kChanged: return "changed";
  }
  return "changed";
}

std::string where(const SourceLocation& at, const std::string& fallback) {
  const std::string file = at.file.empty() ? fallback : at.file.str();
  return at.known() ? fmt::format("{}:{}:{}", file, at.line, at.column) : file;
}

std::string subject(const ModelChange& c) {
  const std::string derived = c.derived ? " (derived)" : "";
  if (c.field == "link") return fmt::format("link '{}'", c.link);
  return fmt::format("{}{}{}", c.link.empty() ? std::string("model") : "link '" + c.link + "'", ": " + c.field,
                     derived);
}

// GCC-style: the line of the new value (the old one's for a removal), then a note at the old.
void write_text(std::ostream& out, const std::vector<ModelChange>& changes, const std::string& old_name,
                const std::string& new_name) {
  std::string group = "\x01";
  for (const ModelChange& c : changes) {
    if (c.link != group) {
      group = c.link;
      const std::string& file = c.kind == ChangeKind::kRemoved && c.field == "link" ? old_name : new_name;
      out << (group.empty() ? fmt::format("{}: In the model:\n", file)
                            : fmt::format("{}: In link '{}':\n", file, group));
    }
    switch (c.kind) {
      case ChangeKind::kChanged:
        out << fmt::format("{}: changed: {}: {} -> {}\n", where(c.new_source, new_name), subject(c), c.old_value,
                           c.new_value);
        out << fmt::format("{}: note: was {}\n", where(c.old_source, old_name), c.old_value);
        break;
      case ChangeKind::kAdded:
        out << fmt::format("{}: added: {}: {}\n", where(c.new_source, new_name), subject(c), c.new_value);
        break;
      case ChangeKind::kRemoved:
        out << fmt::format("{}: removed: {}: {}\n", where(c.old_source, old_name), subject(c), c.old_value);
        break;
    }
  }
}

std::string json_side(const std::string& value, const SourceLocation& at, const std::string& fallback, bool present) {
  if (!present) return "null";
  return fmt::format(R"({{"value": {}, "file": {}, "line": {}, "column": {}}})", text::json_quote(value),
                     text::json_quote(at.file.empty() ? fallback : at.file.str()), at.line, at.column);
}

void write_json(std::ostream& out, const std::vector<ModelChange>& changes, const std::string& old_name,
                const std::string& new_name, double tolerance) {
  std::size_t counts[3] = {0, 0, 0};
  out << "{\n  \"version\": 1,\n";
  out << fmt::format("  \"tool\": {{\"name\": \"bodydiff\", \"version\": \"{}\"}},\n", BODYFMT_VERSION);
  out << fmt::format("  \"old\": {},\n  \"new\": {},\n  \"tolerance\": {},\n", text::json_quote(old_name),
                     text::json_quote(new_name), tolerance);
  out << "  \"changes\": [";
  for (std::size_t i = 0; i < changes.size(); ++i) {
    const ModelChange& c = changes[i];
    ++counts[static_cast<int>(c.kind)];
    out << (i ? ",\n    " : "\n    ");
    out << fmt::format(R"({{"kind": "{}", "link": {}, "field": {}, "derived": {}, "old": {}, "new": {}}})",
                       kind_name(c.kind), c.link.empty() ? "null" : text::json_quote(c.link), text::json_quote(c.field),
                       c.derived, json_side(c.old_value, c.old_source, old_name, c.kind != ChangeKind::kAdded),
                       json_side(c.new_value, c.new_source, new_name, c.kind != ChangeKind::kRemoved));
  }
  out << (changes.empty() ? "],\n" : "\n  ],\n");
  out << fmt::format("  \"summary\": {{\"changes\": {}, \"added\": {}, \"removed\": {}, \"changed\": {}}}\n}}\n",
                     changes.size(), counts[0], counts[1], counts[2]);
}

// Prints the errors that kept a model from loading.
void print_fatal(tools::Front& front, CollectingSink& sink) {
  std::vector<Diagnostic> fatal;
  for (Diagnostic& d : sink.diagnostics())
    if (d.severity >= Severity::kError) fatal.push_back(std::move(d));
  front.print(std::move(fatal));
}

// Loads quietly: a model's own findings are bodycheck's business; only a model that cannot be
// loaded at all stops bodydiff, with its diagnostics.
std::optional<Model> load_quietly(tools::Front& front, const std::string& path, const std::string& name) {
  CollectingSink sink;
  std::optional<Model> model;
  if (name.empty()) {
    if (auto input = front.open_input(path, sink)) model = front.load(*input, sink);
  } else {
    // A git temporary file: loaded under the name of the file in the work tree, so that relative
    // URIs resolve there and locations name it.
    // Bounded like every file read: git hands any path it is given (/dev/zero, a FIFO).
    std::string why;
    if (std::optional<std::string> text = read_regular_file(path, front.load_options().max_file_bytes, why))
      model = load_body_string(*text, name, front.load_options(), sink);
    else
      report_rule(sink, "io-read", SourceLocation{path, 0, 0}, "cannot read \"" + path + "\": " + why);
  }
  if (!model) print_fatal(front, sink);
  return model;
}

// The same for a text read from git, loaded under the work-tree path `name`.
std::optional<Model> load_text_quietly(tools::Front& front, const std::string& text, const std::string& name) {
  CollectingSink sink;
  std::optional<Model> model = load_body_string(text, name, front.load_options(), sink);
  if (!model) print_fatal(front, sink);
  return model;
}

// Renames `from` in the old side's locations to `to` (a work-tree path to git's a/ side, or
// to REV:PATH).
void name_old_side(std::vector<ModelChange>& changes, const std::string& from, const std::string& to) {
  for (ModelChange& c : changes)
    if (c.old_source.file == from) c.old_source.file = FileName(to);
}

// Renames the work-tree path in locations to git's a/ and b/ sides.
void name_sides(std::vector<ModelChange>& changes, const std::string& path) {
  name_old_side(changes, path, "a/" + path);
  for (ModelChange& c : changes)
    if (c.new_source.file == path) c.new_source.file = FileName("b/" + path);
}

}  // namespace

int main(int argc, char** argv) {
  tools::Front front("bodydiff", "Show what changed between two Choreonoid .body models, compared as loaded models",
                     {/*many_inputs=*/true, /*exporter=*/false});
  std::string format = "text";
  ModelDiffOptions options;
  bool no_derived = false, textconv = false, git = false;
  auto& app = front.app();
  app.get_option("paths")->description(
      "OLD.body NEW.body (- for standard input); with --textconv one file; with --git "
      "git's seven arguments");
  app.add_option("--format", format, "output format: text (GCC-style) or json (docs/bodydiff-json.md)")
      ->check(CLI::IsMember({"text", "json"}));
  app.add_option("--tolerance", options.tolerance, "numbers equal when |a - b| <= T * max(1, |a|, |b|) (default 1e-9)")
      ->check(tools::number_above_zero(true));
  app.add_flag("--no-derived", no_derived,
               "do not report derived effects (total mass, centre of mass, world frames, bounding boxes)");
  app.add_flag("--textconv", textconv, "print the canonical text form of one model (git's diff.<driver>.textconv)");
  app.add_flag("--git", git,
               "act as git's external diff driver: PATH OLD-FILE OLD-HEX OLD-MODE NEW-FILE NEW-HEX NEW-MODE; "
               "exits 0 when the models differ, as git expects");
  std::string git_rev;
  auto* git_rev_option =
      app.add_option("--git-rev", git_rev,
                     "compare each FILE with its version at git revision REV (a file not there is new); for CI")
          ->type_name("REV");
  bool staged = false;
  app.add_flag("--staged", staged,
               "compare each FILE as staged in git's index with its version at HEAD (a file new to HEAD, or any "
               "before the first commit, is new); exits 0 when they differ: a report, for the pre-commit stage")
      ->excludes(git_rev_option);
  if (auto code = front.parse(argc, argv)) return *code;
  options.derived = !no_derived;
  const std::vector<std::string>& args = front.inputs();

  if (textconv) {
    if (args.size() != 1) {
      front.print_error("--textconv takes one file");
      return tools::kExitFatal;
    }
    auto model = load_quietly(front, args[0], "");
    if (!model) return tools::kExitFatal;
    std::cout << canonical_text(*model);
    return tools::kExitClean;
  }

  if (git) {
    // git passes 7 arguments, or 9 for a rename (then the new path and a similarity header).
    if (args.size() != 7 && args.size() != 9) {
      front.print_error(fmt::format("--git takes git's 7 (or 9) arguments, not {}", args.size()));
      return tools::kExitFatal;
    }
    const std::string& path = args[0];
    const std::string& new_path = args.size() == 9 ? args[7] : path;
    const bool old_absent = args[1] == "/dev/null", new_absent = args[4] == "/dev/null";
    std::optional<Model> old_model = old_absent ? Model{} : load_quietly(front, args[1], path);
    std::optional<Model> new_model = new_absent ? Model{} : load_quietly(front, args[4], new_path);
    if (!old_model || !new_model) return tools::kExitFatal;
    std::vector<ModelChange> changes = diff_models(*old_model, *new_model, options);
    name_sides(changes, path);
    if (new_path != path) name_sides(changes, new_path);
    if (changes.empty()) return tools::kExitClean;
    std::cout << fmt::format("bodydiff a/{} b/{}\n", path, new_path);
    if (format == "json")
      write_json(std::cout, changes, "a/" + path, "b/" + new_path, options.tolerance);
    else
      write_text(std::cout, changes, "a/" + path, "b/" + new_path);
    return tools::kExitClean;
  }

  if (!git_rev.empty() || staged) {
    const std::string option = staged ? "--staged" : "--git-rev";
    std::string why;
    if (staged) {
      // Before the first commit there is no HEAD: every staged model is new. Outside a
      // repository, reading the index below fails with git's message.
      if (tools::git_commit_exists("HEAD", why)) git_rev = "HEAD";
    } else if (!tools::git_commit_exists(git_rev, why)) {
      front.print_error("--git-rev: " + why);
      return tools::kExitFatal;
    }
    if (args.empty()) {
      front.print_error(option + " takes the model files to compare");
      return tools::kExitFatal;
    }
    int code = tools::kExitClean;
    std::vector<std::string> documents;
    for (const std::string& file : args) {
      // git reads paths from the working folder; an absolute one would be taken from the
      // repository's top (and missed there), so it is made relative first.
      std::filesystem::path given(file);
      if (given.is_absolute()) given = given.lexically_relative(std::filesystem::current_path());
      const std::string path = given.lexically_normal().string();
      const std::string old_name = (git_rev.empty() ? std::string("HEAD") : git_rev) + ":" + path;
      auto fail = [&](const std::string& why) {
        front.print_error(fmt::format("{}: {}: {}", option, file, why));
        code = tools::kExitFatal;
      };
      if (path.empty() || std::filesystem::is_directory(path)) {
        fail("not a model file (a folder)");
        continue;
      }
      tools::GitFile old_file;
      old_file.absent = true;  // before the first commit, every staged model is new
      if (!git_rev.empty()) old_file = tools::git_show(git_rev, path);
      if (!old_file.text && !old_file.absent) {
        fail(old_file.why);
        continue;
      }
      std::optional<Model> old_model = Model{};
      if (old_file.text) {
        CollectingSink sink;
        old_model = load_body_string(*old_file.text, path, front.load_options(), sink);
        if (!old_model) {
          front.print_error(fmt::format("{} cannot be loaded", old_name));
          code = tools::kExitFatal;
          continue;
        }
      }
      std::optional<Model> new_model = Model{};
      if (staged) {
        // The index's text, loaded under the work-tree path so that its meshes and included
        // files resolve there; a file not in the index is deleted.
        const tools::GitFile staged_file = tools::git_show("", path);
        if (!staged_file.text && !staged_file.absent) {
          fail(staged_file.why);
          continue;
        }
        if (staged_file.text) new_model = load_text_quietly(front, *staged_file.text, path);
        if (staged_file.absent && old_file.absent) {
          fail(staged_file.why);  // in neither: mistyped, or never added
          continue;
        }
      } else if (std::filesystem::exists(path)) {
        new_model = load_quietly(front, path, "");
      } else if (old_file.absent) {
        fail(old_file.why + ", nor in the working tree");
        continue;
      }
      if (!new_model) {
        code = tools::kExitFatal;
        continue;
      }
      std::vector<ModelChange> changes = diff_models(*old_model, *new_model, options);
      name_old_side(changes, path, old_name);
      if (format == "json") {
        std::ostringstream doc;
        write_json(doc, changes, old_name, path, options.tolerance);
        documents.push_back(doc.str());
      } else {
        write_text(std::cout, changes, old_name, path);
      }
      if (!changes.empty() && code == tools::kExitClean && !staged) code = tools::kExitFindings;
    }
    if (format == "json") {
      std::cout << "[\n";
      for (std::size_t i = 0; i < documents.size(); ++i) std::cout << (i ? ",\n" : "") << documents[i];
      std::cout << "]\n";
    }
    return code;
  }

  if (args.size() != 2) {
    front.print_error(
        fmt::format("expected OLD.body NEW.body, got {} file{}", args.size(), args.size() == 1 ? "" : "s"));
    return tools::kExitFatal;
  }
  if (args[0] == "-" && args[1] == "-") {
    front.print_error("only one of the two models can be read from standard input");
    return tools::kExitFatal;
  }
  auto old_model = load_quietly(front, args[0], "");
  auto new_model = load_quietly(front, args[1], "");
  if (!old_model || !new_model) return tools::kExitFatal;
  const std::vector<ModelChange> changes = diff_models(*old_model, *new_model, options);
  if (format == "json")
    write_json(std::cout, changes, old_model->source_file, new_model->source_file, options.tolerance);
  else
    write_text(std::cout, changes, old_model->source_file, new_model->source_file);
  std::cout.flush();
  if (!std::cout) return tools::kExitFatal;
  return changes.empty() ? tools::kExitClean : tools::kExitFindings;
}
