// bodydiff: what changed between two .body models, compared as loaded models, not as text.
// Exit codes as diff(1): 0 the same within the tolerance, 1 they differ, 2 usage or a model that
// cannot be loaded. --textconv prints a canonical text form for git; --git is git's external
// diff driver (which must exit 0 when files differ, or git stops).

#include "diff_modes.h"
#include "front.h"
#include "number_options.h"

using namespace bodyfmt;
using namespace bodyfmt::tools;

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
  const DiffRun run{front, options, format};
  if (textconv) return print_textconv(run, args);
  if (git) return git_diff_driver(run, args);
  if (!git_rev.empty() || staged) return diff_against_git(run, args, git_rev, staged);
  return diff_two_files(run, args);
}
