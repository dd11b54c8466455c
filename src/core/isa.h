/* Internal: the vector instruction sets a kernel can be compiled for, and
 * the widest the CPU runs (isa.c).
 *
 * The core is built for baseline x86-64 (SSE2: two doubles per vector). Its
 * hot elementwise loops are also compiled for AVX2 (four) and AVX-512F
 * (eight) through SS_TARGET_*, and run in the widest the CPU has. Only
 * correctly rounded IEEE operations (+ - * / sqrt, compares) run in the
 * lanes and the core is compiled with -ffp-contract=off, so that no
 * multiply and add are fused where the wider sets offer FMA: every width
 * gives the same bits, on any x86-64 (test_energy_membrane, test_walk). */
#ifndef SKIN_SIM_ISA_H
#define SKIN_SIM_ISA_H

enum ss_isa {
  SS_ISA_BASE = 0,   /* what the compiler targets (SSE2 on x86-64) */
  SS_ISA_AVX2 = 1,   /* x86-64 with AVX2 */
  SS_ISA_AVX512 = 2, /* x86-64 with AVX-512F */
  SS_ISA_COUNT = 3
};

#if defined(__GNUC__) && defined(__x86_64__)
#define SS_ISA_WIDE 1 /* the AVX2 and AVX-512 variants are compiled */
#define SS_TARGET_AVX2 __attribute__((target("avx2")))
#define SS_TARGET_AVX512 __attribute__((target("avx512f")))
#endif

/* On a kernel's body shared by the variants: inlined into each, so that
 * each is compiled for its own instruction set. */
#if defined(__GNUC__)
#define SS_ALWAYS_INLINE __attribute__((always_inline))
#else
#define SS_ALWAYS_INLINE
#endif

/* A kernel in each instruction set: SS_ISA_VARIANTS(name, (params), body)
 * defines the static void functions name_base, name_avx2 and name_avx512
 * (the last two only where SS_ISA_WIDE), each with the parameter list
 * params and the body given (a call of the kernel's SS_ALWAYS_INLINE body,
 * so that each is compiled for its own set); SS_ISA_CALL(isa, name, (args))
 * calls the one for isa (base for an isa not compiled). */
#ifdef SS_ISA_WIDE
#define SS_ISA_VARIANTS(name, params, ...)                        \
  static void name##_base params { __VA_ARGS__ }                  \
  SS_TARGET_AVX2 static void name##_avx2 params { __VA_ARGS__ }   \
  SS_TARGET_AVX512 static void name##_avx512 params { __VA_ARGS__ }
#define SS_ISA_CALL(isa, name, args)                                              \
  ((isa) == SS_ISA_AVX512 ? name##_avx512 args                                    \
                          : (isa) == SS_ISA_AVX2 ? name##_avx2 args : name##_base args)
#else
#define SS_ISA_VARIANTS(name, params, ...) static void name##_base params { __VA_ARGS__ }
#define SS_ISA_CALL(isa, name, args) ((void)(isa), name##_base args)
#endif

/* 1 if this CPU runs kernels compiled for isa (and they were compiled). */
int ss_isa_supported(int isa);
/* The widest supported. */
int ss_isa_best(void);
const char *ss_isa_name(int isa);

#endif
