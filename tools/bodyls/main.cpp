// bodyls: the language server for Choreonoid Body files (README "bodyls").
#include "server.h"

int main(int argc, char** argv) { return bodyfmt::lsp::run_server(argc, argv); }
