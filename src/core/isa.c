/* Which instruction sets this CPU runs (isa.h). */
#include "isa.h"

int ss_isa_supported(int isa) {
  switch (isa) {
  case SS_ISA_BASE:
    return 1;
#ifdef SS_ISA_WIDE
  case SS_ISA_AVX2:
    return __builtin_cpu_supports("avx2") != 0;
  case SS_ISA_AVX512:
    return __builtin_cpu_supports("avx512f") != 0;
#endif
  default:
    return 0;
  }
}

int ss_isa_best(void) {
  for (int isa = SS_ISA_COUNT - 1; isa > SS_ISA_BASE; isa--)
    if (ss_isa_supported(isa))
      return isa;
  return SS_ISA_BASE;
}

const char *ss_isa_name(int isa) {
  switch (isa) {
  case SS_ISA_BASE:
    return "base";
  case SS_ISA_AVX2:
    return "avx2";
  case SS_ISA_AVX512:
    return "avx512";
  default:
    return "unknown";
  }
}
