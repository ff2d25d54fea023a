#pragma once
// Forward-mode automatic differentiation: a dual number carries a value and N
// partial derivatives. Used to derive force = -dV/dq and velocity = dT/dp from
// the user's potential and kinetic energy, and (nested) to differentiate a
// whole numerical flow.
#include <array>
#include <cmath>
#include <concepts>
#include <numbers>
#include <type_traits>

#include <Eigen/Core>

namespace sympl {

template <class T, int N>
struct dual {
    static_assert(N >= 1, "a dual number needs at least one derivative direction");
    T value{};
    std::array<T, N> grad{};

    dual() = default;
    // A constant: zero derivative. Implicit so that literals mix freely.
    template <class U>
        requires std::is_arithmetic_v<U>
    dual(U v) : value(static_cast<T>(v)) { grad.fill(T(0)); }
    dual(const T& v)
        requires(!std::is_arithmetic_v<T>)
        : value(v) { grad.fill(T(0)); }

    // The independent variable number `direction` (0-based) with value v.
    static dual variable(const T& v, int direction) {
        dual d(v);
        d.grad[direction] = T(1);
        return d;
    }

    // A dual never becomes a plain number silently: that would drop its
    // derivatives. An explicit std::sqrt(x), std::exp(x), ... on a dual arrives
    // here and stops the build with the fix.
    operator T() const
        requires std::is_floating_point_v<T>
    {
        static_assert(sizeof(T) == 0,
                      "sympl::dual: a std:: math function was called on a dual number (e.g. std::sqrt(x)), which would "
                      "drop its derivatives; write `using std::sqrt; sqrt(x)` so that the dual overload is found");
        return value;
    }

    dual& operator+=(const dual& o) {
        value += o.value;
        for (int i = 0; i < N; ++i) grad[i] += o.grad[i];
        return *this;
    }
    dual& operator-=(const dual& o) {
        value -= o.value;
        for (int i = 0; i < N; ++i) grad[i] -= o.grad[i];
        return *this;
    }
    dual& operator*=(const dual& o) {
        for (int i = 0; i < N; ++i) grad[i] = grad[i] * o.value + value * o.grad[i];
        value *= o.value;
        return *this;
    }
    dual& operator/=(const dual& o) {
        const T inv = T(1) / o.value;
        value *= inv;
        for (int i = 0; i < N; ++i) grad[i] = (grad[i] - value * o.grad[i]) * inv;
        return *this;
    }
};

namespace detail {
template <class X>
struct is_dual : std::false_type {};
template <class T, int N>
struct is_dual<dual<T, N>> : std::true_type {};
}  // namespace detail

// Value of a (possibly nested) dual number, down to the plain scalar.
template <class X>
constexpr auto primal(const X& x) {
    if constexpr (detail::is_dual<X>::value)
        return primal(x.value);
    else
        return x;
}

// pi in the scalar S: std::numbers::pi_v for a floating-point S; for a dual
// number, its primal type's pi converted (derivative parts zero); for other
// scalars (extended-precision classes), long double's pi converted.
template <class S>
constexpr S pi_of() {
    using P = std::decay_t<decltype(primal(std::declval<S>()))>;
    if constexpr (std::floating_point<S>) return std::numbers::pi_v<S>;
    else if constexpr (!std::same_as<P, S>) return S(pi_of<P>());
    else return S(std::numbers::pi_v<long double>);
}

// Scalars that mix with dual<T,N>: T itself and plain arithmetic types.
template <class U, class T>
concept dual_operand = std::is_arithmetic_v<U> || std::same_as<U, T>;

template <class T, int N> dual<T, N> operator+(dual<T, N> a, const dual<T, N>& b) { return a += b; }
template <class T, int N> dual<T, N> operator-(dual<T, N> a, const dual<T, N>& b) { return a -= b; }
template <class T, int N> dual<T, N> operator*(dual<T, N> a, const dual<T, N>& b) { return a *= b; }
template <class T, int N> dual<T, N> operator/(dual<T, N> a, const dual<T, N>& b) { return a /= b; }
template <class T, int N> dual<T, N> operator+(const dual<T, N>& a) { return a; }
template <class T, int N> dual<T, N> operator-(dual<T, N> a) {
    a.value = -a.value;
    for (auto& g : a.grad) g = -g;
    return a;
}

// Mixed operations with a constant: cheaper than promoting the constant.
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator+(dual<T, N> a, const U& c) { a.value += T(c); return a; }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator+(const U& c, dual<T, N> a) { a.value += T(c); return a; }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator-(dual<T, N> a, const U& c) { a.value -= T(c); return a; }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator-(const U& c, const dual<T, N>& a) { return -(a - c); }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator*(dual<T, N> a, const U& c) {
    const T k(c);
    a.value *= k;
    for (auto& g : a.grad) g *= k;
    return a;
}
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator*(const U& c, const dual<T, N>& a) { return a * c; }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator/(const dual<T, N>& a, const U& c) { return a * (T(1) / T(c)); }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> operator/(const U& c, const dual<T, N>& a) { return dual<T, N>(T(c)) / a; }

// Comparisons look at the value only (branches in V(q) follow the primal path).
template <class T, int N> bool operator==(const dual<T, N>& a, const dual<T, N>& b) { return a.value == b.value; }
template <class T, int N> auto operator<=>(const dual<T, N>& a, const dual<T, N>& b) { return a.value <=> b.value; }
template <class T, int N, class U> requires dual_operand<U, T>
bool operator==(const dual<T, N>& a, const U& c) { return a.value == T(c); }
template <class T, int N, class U> requires dual_operand<U, T>
auto operator<=>(const dual<T, N>& a, const U& c) { return a.value <=> T(c); }

// Chain rule: f(a) with f'(a) given.
template <class T, int N>
dual<T, N> chain(const dual<T, N>& a, const T& f, const T& dfda) {
    dual<T, N> r;
    r.value = f;
    for (int i = 0; i < N; ++i) r.grad[i] = dfda * a.grad[i];
    return r;
}

// Elementary functions, found by argument-dependent lookup (also by Eigen).
template <class T, int N> dual<T, N> sqrt(const dual<T, N>& a) {
    using std::sqrt;
    const T s = sqrt(a.value);
    return chain(a, s, T(0.5) / s);
}
template <class T, int N> dual<T, N> sin(const dual<T, N>& a) {
    using std::sin; using std::cos;
    return chain(a, sin(a.value), cos(a.value));
}
template <class T, int N> dual<T, N> cos(const dual<T, N>& a) {
    using std::sin; using std::cos;
    return chain(a, cos(a.value), -sin(a.value));
}
template <class T, int N> dual<T, N> tan(const dual<T, N>& a) {
    using std::tan;
    const T t = tan(a.value);
    return chain(a, t, T(1) + t * t);
}
template <class T, int N> dual<T, N> exp(const dual<T, N>& a) {
    using std::exp;
    const T e = exp(a.value);
    return chain(a, e, e);
}
template <class T, int N> dual<T, N> log(const dual<T, N>& a) {
    using std::log;
    return chain(a, log(a.value), T(1) / a.value);
}
template <class T, int N> dual<T, N> sinh(const dual<T, N>& a) {
    using std::sinh; using std::cosh;
    return chain(a, sinh(a.value), cosh(a.value));
}
template <class T, int N> dual<T, N> cosh(const dual<T, N>& a) {
    using std::sinh; using std::cosh;
    return chain(a, cosh(a.value), sinh(a.value));
}
template <class T, int N> dual<T, N> tanh(const dual<T, N>& a) {
    using std::tanh;
    const T t = tanh(a.value);
    return chain(a, t, T(1) - t * t);
}
template <class T, int N> dual<T, N> atan(const dual<T, N>& a) {
    using std::atan;
    return chain(a, atan(a.value), T(1) / (T(1) + a.value * a.value));
}
template <class T, int N> dual<T, N> asin(const dual<T, N>& a) {
    using std::asin; using std::sqrt;
    return chain(a, asin(a.value), T(1) / sqrt(T(1) - a.value * a.value));
}
template <class T, int N> dual<T, N> acos(const dual<T, N>& a) {
    using std::acos; using std::sqrt;
    return chain(a, acos(a.value), T(-1) / sqrt(T(1) - a.value * a.value));
}
template <class T, int N> dual<T, N> asinh(const dual<T, N>& a) {
    using std::asinh; using std::sqrt;
    return chain(a, asinh(a.value), T(1) / sqrt(a.value * a.value + T(1)));
}
template <class T, int N> dual<T, N> acosh(const dual<T, N>& a) {
    using std::acosh; using std::sqrt;
    return chain(a, acosh(a.value), T(1) / sqrt(a.value * a.value - T(1)));
}
template <class T, int N> dual<T, N> atanh(const dual<T, N>& a) {
    using std::atanh;
    return chain(a, atanh(a.value), T(1) / (T(1) - a.value * a.value));
}
template <class T, int N> dual<T, N> cbrt(const dual<T, N>& a) {
    using std::cbrt;
    const T c = cbrt(a.value);
    return chain(a, c, T(1) / (T(3) * c * c));
}
template <class T, int N> dual<T, N> log1p(const dual<T, N>& a) {
    using std::log1p;
    return chain(a, log1p(a.value), T(1) / (T(1) + a.value));
}
template <class T, int N> dual<T, N> expm1(const dual<T, N>& a) {
    using std::expm1; using std::exp;
    return chain(a, expm1(a.value), exp(a.value));
}
template <class T, int N> dual<T, N> log2(const dual<T, N>& a) {
    using std::log2; using std::log;
    return chain(a, log2(a.value), T(1) / (a.value * log(T(2))));
}
template <class T, int N> dual<T, N> log10(const dual<T, N>& a) {
    using std::log10; using std::log;
    return chain(a, log10(a.value), T(1) / (a.value * log(T(10))));
}
template <class T, int N> dual<T, N> exp2(const dual<T, N>& a) {
    using std::exp2; using std::log;
    const T e = exp2(a.value);
    return chain(a, e, e * log(T(2)));
}
// atan2(y, x) and hypot(x, y) in every mix of dual and plain arguments.
template <class T, int N> dual<T, N> atan2(const dual<T, N>& y, const dual<T, N>& x) {
    using std::atan2;
    const T r2 = x.value * x.value + y.value * y.value;
    dual<T, N> r;
    r.value = atan2(y.value, x.value);
    for (int i = 0; i < N; ++i) r.grad[i] = (x.value * y.grad[i] - y.value * x.grad[i]) / r2;
    return r;
}
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> atan2(const dual<T, N>& y, const U& x) { return atan2(y, dual<T, N>(x)); }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> atan2(const U& y, const dual<T, N>& x) { return atan2(dual<T, N>(y), x); }
template <class T, int N> dual<T, N> hypot(const dual<T, N>& x, const dual<T, N>& y) {
    using std::hypot;
    const T h = hypot(x.value, y.value);
    dual<T, N> r;
    r.value = h;
    for (int i = 0; i < N; ++i) r.grad[i] = (x.value * x.grad[i] + y.value * y.grad[i]) / h;
    return r;
}
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> hypot(const dual<T, N>& x, const U& y) { return hypot(x, dual<T, N>(y)); }
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> hypot(const U& x, const dual<T, N>& y) { return hypot(dual<T, N>(x), y); }
template <class T, int N> dual<T, N> abs(const dual<T, N>& a) {
    return a.value < T(0) ? -a : a;
}
template <class T, int N> dual<T, N> fabs(const dual<T, N>& a) { return abs(a); }
template <class T, int N> dual<T, N> abs2(const dual<T, N>& a) { return a * a; }
template <class T, int N> dual<T, N> pow(const dual<T, N>& a, const T& e) {
    using std::pow;
    const T pm1 = pow(a.value, e - T(1));
    return chain(a, pm1 * a.value, e * pm1);
}
template <class T, int N, class U> requires std::is_arithmetic_v<U> && (!std::same_as<U, T>)
dual<T, N> pow(const dual<T, N>& a, U e) { return pow(a, T(e)); }
template <class T, int N> dual<T, N> pow(const dual<T, N>& a, const dual<T, N>& e) {
    using std::pow; using std::log;
    // d(a^e) = e a^(e-1) da + a^e log(a) de; the log term only where e varies,
    // so that a <= 0 with a constant integer e stays finite.
    const T pm1 = pow(a.value, e.value - T(1)), v = pm1 * a.value;
    bool e_varies = false;
    for (const T& g : e.grad) e_varies = e_varies || g != T(0);
    const T log_a = e_varies ? log(a.value) : T(0);
    dual<T, N> r;
    r.value = v;
    for (int i = 0; i < N; ++i) r.grad[i] = e.value * pm1 * a.grad[i] + (e_varies ? v * log_a * e.grad[i] : T(0));
    return r;
}
template <class T, int N, class U> requires dual_operand<U, T>
dual<T, N> pow(const U& base, const dual<T, N>& e) { return pow(dual<T, N>(base), e); }
template <class T, int N> bool isfinite(const dual<T, N>& a) {
    using std::isfinite;
    if (!isfinite(a.value)) return false;
    for (const auto& g : a.grad)
        if (!isfinite(g)) return false;
    return true;
}

}  // namespace sympl

namespace sympl::detail {
// What Eigen's NumTraits asks of a number type built on T (dual numbers, SIMD
// batches): the type itself as Real and its kin, T's limits converted to it.
// A specialisation adds its costs.
template <class Number, class T>
struct number_traits_over : Eigen::NumTraits<T> {
    using Real = Number;
    using NonInteger = Number;
    using Nested = Number;
    using Literal = Number;
    static Real epsilon() { return Real(Eigen::NumTraits<T>::epsilon()); }
    static Real dummy_precision() { return Real(Eigen::NumTraits<T>::dummy_precision()); }
    static Real highest() { return Real(Eigen::NumTraits<T>::highest()); }
    static Real lowest() { return Real(Eigen::NumTraits<T>::lowest()); }
    static int digits10() { return Eigen::NumTraits<T>::digits10(); }
};
}  // namespace sympl::detail

// Eigen needs to know how a dual behaves as a matrix scalar.
namespace Eigen {
template <class T, int N>
struct NumTraits<sympl::dual<T, N>> : sympl::detail::number_traits_over<sympl::dual<T, N>, T> {
    enum {
        IsComplex = 0,
        IsInteger = 0,
        IsSigned = 1,
        RequireInitialization = 1,
        ReadCost = (N + 1) * NumTraits<T>::ReadCost,
        AddCost = (N + 1) * NumTraits<T>::AddCost,
        MulCost = (2 * N + 1) * NumTraits<T>::MulCost
    };
};
template <class T, int N, class U>
    requires std::is_arithmetic_v<U>
struct ScalarBinaryOpTraits<sympl::dual<T, N>, U, internal::scalar_product_op<sympl::dual<T, N>, U>> {
    using ReturnType = sympl::dual<T, N>;
};
template <class T, int N, class U>
    requires std::is_arithmetic_v<U>
struct ScalarBinaryOpTraits<U, sympl::dual<T, N>, internal::scalar_product_op<U, sympl::dual<T, N>>> {
    using ReturnType = sympl::dual<T, N>;
};
template <class T, int N, class U>
    requires std::is_arithmetic_v<U>
struct ScalarBinaryOpTraits<sympl::dual<T, N>, U, internal::scalar_quotient_op<sympl::dual<T, N>, U>> {
    using ReturnType = sympl::dual<T, N>;
};
}  // namespace Eigen
