#pragma once

// The allocator policy of Lookout's programs (the CLI and the benchmarks).
//
// Why: a pipeline cycle allocates and frees the same few megabytes every cycle (the grid's
// associations, target index and scratch layers, the lidar chain's clouds). glibc hands blocks
// above its mmap threshold (128 kB, raised only when such a block is freed) back to the kernel
// on free, and trims the heap's top above twice that; the next cycle then page-faults every
// page back in, zeroed by the kernel. On the simulator's junction that was 611 page faults in
// each grid update, a third of its time on this project's virtual machine (docs/PERFORMANCE.md,
// "Serial passes, load balance, page faults"). Keeping freed memory costs the program's
// high-water mark, which a pipeline reaches in its first cycles anyway.

namespace lookout {

// Keeps memory the program frees for its next allocations: with glibc, a fixed mmap threshold
// of 32 MiB (the largest it takes; blocks below it come from the heap and stay there) and a trim
// threshold of 1 GiB. Call once, first thing in main, before any thread starts. Returns whether
// the allocator took the policy (false off glibc: nothing is changed).
bool KeepFreedMemory();

}  // namespace lookout
