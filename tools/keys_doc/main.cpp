// keys_doc: prints docs/keys.md (libbodyfmt's key table as Markdown). No options.
#include <bodyfmt/body_keys.h>

#include <cstdio>

int main() {
  const std::string text = bodyfmt::body_keys_markdown();
  std::fwrite(text.data(), 1, text.size(), stdout);
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return 0;
  std::fputs("keys_doc: error: cannot write to standard output\n", stderr);
  return 2;
}
