#pragma once
// W numbers in one SIMD register: the scalar of a state that carries W
// trajectories in lockstep (ensemble.hpp). Every operation acts lane by lane,
// with the same IEEE operation a single trajectory would use, so a lane of a
// batch follows the same arithmetic as the trajectory run alone; the stepper,
// the Hamiltonians and the dual numbers run unchanged on it.
//
// The lanes use the GCC/Clang vector extension, which compiles to the
// machine's vector instructions where they exist and to pairs or quadruples
// of narrower ones where not.
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include <Eigen/Core>

#include "../core/dual.hpp"  // detail::number_traits_over

namespace sympl {

// Doubles per vector register of the target the code is compiled for:
// 8 with AVX-512, 4 with AVX, 2 with SSE2 or NEON, 1 otherwise.
constexpr int native_double_width =
#if defined(__AVX512F__)
    8;
#elif defined(__AVX__)
    4;
#elif defined(__SSE2__) || defined(__ARM_NEON) || defined(__ALTIVEC__)
    2;
#else
    1;
#endif

template <class T, int W>
struct batch {
    static_assert(std::is_floating_point_v<T>, "batch: lanes of a floating-point type");
    static_assert(W >= 1 && (W & (W - 1)) == 0, "batch: the lane count is a power of two");
    using lanes_type [[gnu::vector_size(sizeof(T) * W)]] = T;
    static constexpr int width = W;

    lanes_type v;

    batch() : v{} {}
    // A number broadcast to every lane (implicit, so that literals mix freely).
    template <class U>
        requires std::is_arithmetic_v<U>
    batch(U x) {
        for (int i = 0; i < W; ++i) v[i] = static_cast<T>(x);
    }
    static batch from_lanes(lanes_type l) {
        batch b;
        b.v = l;
        return b;
    }

    T operator[](int lane) const { return v[lane]; }
    // Lane 0, explicitly: error messages print a step size, the same in every lane.
    explicit operator T() const { return v[0]; }
    void set(int lane, T x) { v[lane] = x; }

    batch& operator+=(const batch& o) { v += o.v; return *this; }
    batch& operator-=(const batch& o) { v -= o.v; return *this; }
    batch& operator*=(const batch& o) { v *= o.v; return *this; }
    batch& operator/=(const batch& o) { v /= o.v; return *this; }
};

template <class T, int W> batch<T, W> operator+(batch<T, W> a, const batch<T, W>& b) { return a += b; }
template <class T, int W> batch<T, W> operator-(batch<T, W> a, const batch<T, W>& b) { return a -= b; }
template <class T, int W> batch<T, W> operator*(batch<T, W> a, const batch<T, W>& b) { return a *= b; }
template <class T, int W> batch<T, W> operator/(batch<T, W> a, const batch<T, W>& b) { return a /= b; }
template <class T, int W> batch<T, W> operator+(const batch<T, W>& a) { return a; }
template <class T, int W> batch<T, W> operator-(const batch<T, W>& a) { return batch<T, W>::from_lanes(-a.v); }

template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator+(batch<T, W> a, U c) { return a += batch<T, W>(c); }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator+(U c, const batch<T, W>& a) { return batch<T, W>(c) + a; }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator-(batch<T, W> a, U c) { return a -= batch<T, W>(c); }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator-(U c, const batch<T, W>& a) { return batch<T, W>(c) - a; }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator*(batch<T, W> a, U c) { return a *= batch<T, W>(c); }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator*(U c, const batch<T, W>& a) { return batch<T, W>(c) * a; }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator/(batch<T, W> a, U c) { return a /= batch<T, W>(c); }
template <class T, int W, class U> requires std::is_arithmetic_v<U>
batch<T, W> operator/(U c, const batch<T, W>& a) { return batch<T, W>(c) / a; }

// Equality holds when it holds in every lane (the stepper's `dt == 0`: dt is
// one number broadcast). There is deliberately no ordering: a branch of a
// Hamiltonian on `r < cutoff` cannot be taken lane by lane, so such a
// Hamiltonian does not compile on batches and runs one trajectory at a time
// (run_ensemble<1>).
template <class T, int W> bool operator==(const batch<T, W>& a, const batch<T, W>& b) {
    for (int i = 0; i < W; ++i)
        if (!(a.v[i] == b.v[i])) return false;
    return true;
}
template <class T, int W, class U> requires std::is_arithmetic_v<U>
bool operator==(const batch<T, W>& a, U c) { return a == batch<T, W>(c); }

namespace detail {
template <class T, int W, class F>
batch<T, W> each_lane(const batch<T, W>& a, F f) {
    batch<T, W> r;
    for (int i = 0; i < W; ++i) r.v[i] = f(a.v[i]);
    return r;
}
}  // namespace detail

// <cmath> lane by lane (found by argument-dependent lookup, like dual's).
#define SYMPL_BATCH_FUNCTION(name)                                                       \
    template <class T, int W>                                                            \
    batch<T, W> name(const batch<T, W>& a) {                                             \
        return detail::each_lane(a, [](T x) { return std::name(x); });                   \
    }
SYMPL_BATCH_FUNCTION(sqrt)
SYMPL_BATCH_FUNCTION(exp)
SYMPL_BATCH_FUNCTION(log)
SYMPL_BATCH_FUNCTION(sin)
SYMPL_BATCH_FUNCTION(cos)
SYMPL_BATCH_FUNCTION(tan)
SYMPL_BATCH_FUNCTION(atan)
SYMPL_BATCH_FUNCTION(sinh)
SYMPL_BATCH_FUNCTION(cosh)
SYMPL_BATCH_FUNCTION(tanh)
SYMPL_BATCH_FUNCTION(cbrt)
SYMPL_BATCH_FUNCTION(abs)
SYMPL_BATCH_FUNCTION(fabs)
#undef SYMPL_BATCH_FUNCTION

template <class T, int W> batch<T, W> pow(const batch<T, W>& a, T e) {
    return detail::each_lane(a, [e](T x) { return std::pow(x, e); });
}
template <class T, int W> batch<T, W> pow(const batch<T, W>& a, int e) {
    return detail::each_lane(a, [e](T x) { return std::pow(x, e); });
}

// The larger of a and b in each lane; a lane where b is NaN keeps a.
template <class T, int W> batch<T, W> lane_max(const batch<T, W>& a, const batch<T, W>& b) {
    return batch<T, W>::from_lanes(b.v > a.v ? b.v : a.v);
}

// True when every lane is finite.
template <class T, int W> bool isfinite(const batch<T, W>& a) {
    for (int i = 0; i < W; ++i)
        if (!std::isfinite(a.v[i])) return false;
    return true;
}

// Writes lane `lane`; a plain number has one lane.
template <class T> void set_lane(T& x, int, T value) requires std::is_arithmetic_v<T> { x = value; }
template <class T, int W> void set_lane(batch<T, W>& x, int lane, T value) { x.v[lane] = value; }

// Lane `lane` of a plain number is the number itself: code that reads lanes
// runs on plain states too.
template <class T> T lane_of(T x, int) requires std::is_arithmetic_v<T> { return x; }
template <class T, int W> T lane_of(const batch<T, W>& x, int lane) { return x.v[lane]; }

template <class X>
struct lanes_of : std::integral_constant<int, 1> {};
template <class T, int W>
struct lanes_of<batch<T, W>> : std::integral_constant<int, W> {};

}  // namespace sympl

// Eigen matrices of batches (the state vectors): a real, non-complex number
// type whose operations cost about as much as a double's.
namespace Eigen {
template <class T, int W>
struct NumTraits<sympl::batch<T, W>> : sympl::detail::number_traits_over<sympl::batch<T, W>, T> {
    enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 1, AddCost = 1, MulCost = 1 };
};
template <class T, int W, typename BinaryOp>
struct ScalarBinaryOpTraits<sympl::batch<T, W>, T, BinaryOp> {
    using ReturnType = sympl::batch<T, W>;
};
template <class T, int W, typename BinaryOp>
struct ScalarBinaryOpTraits<T, sympl::batch<T, W>, BinaryOp> {
    using ReturnType = sympl::batch<T, W>;
};
}  // namespace Eigen
