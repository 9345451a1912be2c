#include "lookout/app/cli.h"

#include <CLI/CLI.hpp>

namespace lookout::app {

int RunCli(int argc, char** argv) {
  CLI::App cli{"Lookout: perception and collision warning at intersections"};
  cli.require_subcommand(1);
  CLI11_PARSE(cli, argc, argv);
  return 0;
}

}  // namespace lookout::app
