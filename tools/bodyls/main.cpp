// bodyls: the language server for Choreonoid Body files.
#include "server.h"

int main() { return bodyfmt::lsp::run_server(); }
