#pragma once
// A memory hint for the fronts' look-ahead. Internal.

namespace edgefront::detail {

// Asks for the cache line at `p` without waiting for it. On x86 an asm statement: GCC drops
// __builtin_prefetch together with a loop that does nothing else (the look-ahead loops of the
// fronts), as it may drop any loop without effects.
inline void prefetch(const void* p) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p);
#endif
}

}  // namespace edgefront::detail
