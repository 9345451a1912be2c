#include "lookout/core/memory_policy.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace lookout {
namespace {

long MinorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// Allocates `bytes`, writes every byte (so every page is mapped), frees it; returns the page
// faults that took.
long FaultsOfOneCycle(std::size_t bytes) {
  const long before = MinorFaults();
  {
    const std::unique_ptr<char[]> block(new char[bytes]);
    std::memset(block.get(), 1, bytes);
    // Keep the writes: the compiler may not drop them before the free.
    asm volatile("" : : "r"(block.get()) : "memory");
  }
  return MinorFaults() - before;
}

// Under AddressSanitizer the allocator is the sanitizer's, not glibc's.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizedAllocator = true;
#elif defined(__has_feature)
constexpr bool kSanitizedAllocator = __has_feature(address_sanitizer);
#else
constexpr bool kSanitizedAllocator = false;
#endif

#if defined(__GLIBC__)
TEST(MemoryPolicyTest, ACycleThatFreesAndAllocatesAgainFaultsNoPageBackIn) {
  if (kSanitizedAllocator) GTEST_SKIP() << "the sanitizer's allocator replaces glibc's";
  ASSERT_TRUE(KeepFreedMemory());
  constexpr std::size_t kBytes = 4 << 20;  // above glibc's default mmap threshold (128 kB)
  const long first = FaultsOfOneCycle(kBytes);
  const long second = FaultsOfOneCycle(kBytes);
  const long pages = static_cast<long>(kBytes / 4096);
  // The first cycle maps the block's pages; the second finds them kept (a handful of faults
  // from elsewhere in the process at most). Without the policy, each cycle faults all of them.
  EXPECT_GE(first, pages / 2);
  EXPECT_LT(second, pages / 20) << "first cycle " << first << " faults";
}
#endif

}  // namespace
}  // namespace lookout
