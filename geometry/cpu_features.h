/* The processor's features that the vector kernels choose their path by (tensor_derivs.hpp),
   as glibc sees them: CPU_FEATURE_ACTIVE of <sys/platform/x86.h> (glibc 2.33 and newer), which
   also honours GLIBC_TUNABLES's masks, so that a run with glibc.cpu.hwcaps=-AVX2,-FMA takes
   the path of a processor without them, as libm does. A C file: glibc's header is C (its
   inline functions return _Bool). */
#ifndef IGA_GEOMETRY_CPU_FEATURES_H
#define IGA_GEOMETRY_CPU_FEATURES_H

#ifdef __cplusplus
extern "C" {
#endif

/* 1 where AVX2 and FMA are both active, else 0 (0 on processors other than x86-64). */
int iga_avx2_fma_active(void);

#ifdef __cplusplus
}
#endif

#endif
