// Every benchmark program runs under the CLI's allocator policy (lookout/core/memory_policy.h), so
// that its figures are the program's: a steady cycle page-faults nothing back in. Set by this
// initialiser, before main and any thread.

#include "lookout/core/memory_policy.h"

namespace {

[[maybe_unused]] const bool kKeepsFreedMemory = lookout::KeepFreedMemory();

}  // namespace
