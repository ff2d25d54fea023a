#pragma once
// The loops over many bodies in lanes (the Kepler drifts, the test
// particles' field, the encounter checks) run in AVX2 registers, four
// doubles wide, where the CPU has AVX2: chosen at run time, so that the
// library keeps its user's flags (SSE2, two doubles, by x86-64's default;
// never -march=native). Such a loop is compiled a second time for AVX2
// without FMA, every call inside it inlined: each lane computes what the
// SSE2 loop computes, the same operations in the same order, so both give
// the same bits (a test compares them; the measured gain is in
// docs/planetary.md).
#include <atomic>

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#define SYMPL_WIDE_LANES 1
// A function compiled again for AVX2, with every call in it inlined.
#define SYMPL_AVX2_CLONE [[gnu::target("avx2"), gnu::flatten]]
#else
#define SYMPL_WIDE_LANES 0
#define SYMPL_AVX2_CLONE
#endif

// Before a lane loop whose arrays do not overlap, where more arrays are
// involved than the compiler checks at run time (GCC's ivdep; clang's own).
#if defined(__clang__)
#define SYMPL_ARRAYS_APART _Pragma("clang loop vectorize(assume_safety)")
#elif defined(__GNUC__)
#define SYMPL_ARRAYS_APART _Pragma("GCC ivdep")
#else
#define SYMPL_ARRAYS_APART
#endif

namespace sympl {

namespace detail {
inline std::atomic<bool>& wide_lanes_allowed() {
    static std::atomic<bool> allowed{true};
    return allowed;
}
}  // namespace detail

// Whether the lane loops run in AVX2: the CPU has it and use_wide_lanes(false)
// has not turned it off.
inline bool wide_lanes() {
#if SYMPL_WIDE_LANES
    static const bool cpu = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return cpu && detail::wide_lanes_allowed().load(std::memory_order_relaxed);
#else
    return false;
#endif
}

// Off: the lane loops run as the build's flags compile them (the same bits,
// slower where the CPU has AVX2); on (the default): in AVX2 where the CPU has it.
inline void use_wide_lanes(bool on) { detail::wide_lanes_allowed().store(on, std::memory_order_relaxed); }

}  // namespace sympl
