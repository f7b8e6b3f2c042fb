#pragma once
/// Placeholder for the language server's core (replaced by the helper that builds it).

namespace bodyfmt::lsp {

int run_server();

}  // namespace bodyfmt::lsp
