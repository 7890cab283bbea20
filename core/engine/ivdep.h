// MEMBRANE_IVDEP, before a loop: tells the compiler that the loop has no dependence that
// forbids vectorizing it (the caller has checked that every read is of a word the loop does
// not write, or writes before it).
#ifndef MEMBRANE_CORE_ENGINE_IVDEP_H_
#define MEMBRANE_CORE_ENGINE_IVDEP_H_

#if defined(__clang__)
#define MEMBRANE_IVDEP _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define MEMBRANE_IVDEP _Pragma("GCC ivdep")
#else
#define MEMBRANE_IVDEP
#endif

#endif  // MEMBRANE_CORE_ENGINE_IVDEP_H_
