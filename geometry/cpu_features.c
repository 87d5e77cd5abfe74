/* See cpu_features.h. */
#include "geometry/cpu_features.h"

#if defined(__x86_64__)
#include <sys/platform/x86.h>
#endif

int iga_avx2_fma_active(void) {
#if defined(__x86_64__)
  return CPU_FEATURE_ACTIVE(AVX2) && CPU_FEATURE_ACTIVE(FMA);
#else
  return 0;
#endif
}
