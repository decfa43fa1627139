// Runtime dispatch between x86-64 micro-architecture levels for the hot geometry kernels.
// The library itself is compiled with portable flags; a function marked
// SPACETREE_DISPATCH_BY_ISA is compiled three times (AVX-512, AVX2+FMA, baseline SSE2) and the
// dynamic loader picks the best clone for the running CPU once (GNU ifunc). Helpers called from
// such a function must be inline (header) functions so that they are compiled into every clone.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 11 && defined(__x86_64__) && \
    defined(__linux__) && !defined(SPACETREE_NO_ISA_DISPATCH)
#define SPACETREE_DISPATCH_BY_ISA \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define SPACETREE_DISPATCH_BY_ISA
#endif

// For helpers of a dispatched function: without it GCC keeps big helpers out of line, compiled
// for the baseline ISA only (and std::fma there becomes a library call).
#if defined(__GNUC__)
#define SPACETREE_INLINE_INTO_CLONES inline __attribute__((always_inline))
#else
#define SPACETREE_INLINE_INTO_CLONES inline
#endif
