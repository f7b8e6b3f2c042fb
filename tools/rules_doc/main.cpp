// rules_doc: prints docs/rules.md (the rule table as Markdown). No options.
#include <bodyfmt/validate.h>

#include <cstdio>

int main() {
  const std::string text = bodyfmt::validate::rules_markdown();
  std::fwrite(text.data(), 1, text.size(), stdout);
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return 0;
  std::fputs("rules_doc: error: cannot write to standard output\n", stderr);
  return 2;
}
