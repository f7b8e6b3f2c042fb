#include "help_formatter.h"

namespace bodyfmt::tools {

std::string HelpFormatter::make_option_name(const CLI::Option* option, bool is_positional) const {
  std::string name = CLI::Formatter::make_option_name(option, is_positional);
  // CLI11 writes a flag's default value in braces after each of its names: "--fix{safe}".
  for (std::size_t open = name.find('{'); open != std::string::npos; open = name.find('{', open)) {
    const std::size_t close = name.find('}', open);
    if (close == std::string::npos) break;
    name.erase(open, close - open + 1);
  }
  return name;
}

std::string HelpFormatter::make_option_opts(const CLI::Option* option) const {
  const std::string& text = option->get_option_text();
  // An optional value belongs to the name: --fix[=KIND].
  if (text.rfind("[=", 0) == 0) return text;
  return CLI::Formatter::make_option_opts(option);
}

std::shared_ptr<CLI::Formatter> help_formatter() { return std::make_shared<HelpFormatter>(); }

}  // namespace bodyfmt::tools
