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
#include <cmath>
#include <cstddef>
#include <type_traits>

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#define SYMPL_WIDE_LANES 1
// A function compiled again for AVX2, with every call in it inlined.
#define SYMPL_AVX2_CLONE [[gnu::target("avx2"), gnu::flatten]]
#else
#define SYMPL_WIDE_LANES 0
#define SYMPL_AVX2_CLONE
#endif

#if SYMPL_WIDE_LANES
#include <immintrin.h>
#endif

// Before a lane loop whose arrays do not overlap, where more arrays are
// involved than the compiler checks at run time: GCC's ivdep. Nothing for
// clang: its assume_safety also asks for the loop to be vectorised, and
// warns (-Wpass-failed) wherever it cannot be, as on dual numbers or under
// the sanitizers; clang checks the arrays at run time itself.
#if defined(__clang__)
#define SYMPL_ARRAYS_APART
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

namespace detail {
// r[i] = sqrt(x[i]) for i < m (r may be x), doubles in vector registers: a
// loop of std::sqrt does not vectorise (it keeps a branch to set errno), and
// Eigen's packet square root stays two wide inside an AVX2 clone. The square
// root is correctly rounded, so every path gives the same bits; other types
// (dual numbers) take their own sqrt one by one.
template <class T>
inline void square_roots_narrow(const T* x, T* r, std::size_t m) {
    std::size_t i = 0;
#if SYMPL_WIDE_LANES && defined(__SSE2__)
    if constexpr (std::is_same_v<T, double>)
        for (; i + 2 <= m; i += 2) _mm_storeu_pd(r + i, _mm_sqrt_pd(_mm_loadu_pd(x + i)));
#endif
    using std::sqrt;
    for (; i < m; ++i) r[i] = sqrt(x[i]);
}

// Four at a time, for the AVX2 clones (flatten inlines it there).
#if SYMPL_WIDE_LANES
[[gnu::target("avx2")]] inline void square_roots_wide(const double* x, double* r, std::size_t m) {
    std::size_t i = 0;
    for (; i + 4 <= m; i += 4) _mm256_storeu_pd(r + i, _mm256_sqrt_pd(_mm256_loadu_pd(x + i)));
    for (; i < m; ++i) r[i] = std::sqrt(x[i]);
}
#else
inline void square_roots_wide(const double* x, double* r, std::size_t m) { square_roots_narrow(x, r, m); }
#endif

// Wide in the clones, narrow elsewhere.
template <bool Wide, class T>
inline void square_roots(const T* x, T* r, std::size_t m) {
    if constexpr (Wide && std::is_same_v<T, double>)
        square_roots_wide(x, r, m);
    else
        square_roots_narrow(x, r, m);
}
}  // namespace detail

// Off: the lane loops run as the build's flags compile them (the same bits,
// slower where the CPU has AVX2); on (the default): in AVX2 where the CPU has it.
inline void use_wide_lanes(bool on) { detail::wide_lanes_allowed().store(on, std::memory_order_relaxed); }

}  // namespace sympl
