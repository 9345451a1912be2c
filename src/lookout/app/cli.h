#pragma once

namespace lookout::app {

// The `lookout` command line (docs/cli-contract.md). Returns the process exit code:
// 0 success, 2 bad input (one message on stderr naming file, line and field), 1 otherwise.
int RunCli(int argc, char** argv);

}  // namespace lookout::app
