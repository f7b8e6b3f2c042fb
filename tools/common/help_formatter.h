#pragma once
// --help as a person reads it, on CLI11's formatter: a flag that takes an optional value
// (`--fix`, `--fix=geometry`) shows it as `--fix[=KIND]`, not as CLI11's `--fix{safe}` with its
// validator's `:{safe,geometry}` after it. An option whose value may be left out says so in
// its option_text ("[=DENSITY]"), which is written against the name.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace bodyfmt::tools {

class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* option, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* option) const override;
};

/// The formatter every tool's --help uses (Front sets it).
std::shared_ptr<CLI::Formatter> help_formatter();

}  // namespace bodyfmt::tools
