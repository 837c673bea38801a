#pragma once
// Whether this CPU runs the AVX2 row kernels (combine_row.cpp,
// capsule_row.cpp); each keeps a plain fallback giving the same bytes.

namespace sculpt::core {

#if defined(__x86_64__) && defined(__GNUC__)
inline bool cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
  return has;
}
#endif

}  // namespace sculpt::core
