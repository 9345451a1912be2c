#include "lookout/app/cli.h"

int main(int argc, char** argv) { return lookout::app::RunCli(argc, argv); }
