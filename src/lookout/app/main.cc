#include "lookout/app/cli.h"
#include "lookout/core/memory_policy.h"

int main(int argc, char** argv) {
  lookout::KeepFreedMemory();  // before any thread: see memory_policy.h
  return lookout::app::RunCli(argc, argv);
}
