// PUSHOUT_VECTOR_CLONES: a kernel compiled twice, for AVX2 + FMA
// (x86-64-v3) and for plain x86-64, the one for the CPU at hand chosen when
// the program loads (GCC's target_clones, an ifunc). Elsewhere (another
// compiler or architecture) the kernel is compiled once, as usual.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PUSHOUT_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define PUSHOUT_VECTOR_CLONES
#endif
