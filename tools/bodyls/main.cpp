// bodyls: the language server for Choreonoid Body files (docs/tools/bodyls.md).
#include "server.h"

int main(int argc, char** argv) { return bodyfmt::lsp::run_server(argc, argv); }
