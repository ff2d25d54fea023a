#pragma once
// Reverse-mode automatic differentiation: a taped number is a value and the
// index of the operation that made it, recorded on a tape of this thread. One
// evaluation of f records every operation; one backward sweep of the tape then
// gives the whole gradient, at a cost that is a small multiple of evaluating f
// whatever the dimension (Griewank & Walther, Evaluating Derivatives, 2nd ed.
// 2008, ch. 3 and 4). Forward mode (dual.hpp) costs n/8 evaluations for n
// inputs: the library uses this file for gradients of large or dynamic-size
// states (hamiltonian.hpp) and dual numbers where they are cheaper.
//
// The tape keeps its memory between gradients: no allocation once warm. It is
// thread_local, so threads differentiate independently; a gradient must not be
// nested inside another of the same scalar type (refused: reverse_tape::begin).
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "error.hpp"

namespace sympl {

template <class T>
struct taped;

namespace detail {
// One recorded operation: the result's partial derivatives with respect to at
// most two earlier results. A unary operation names itself as its second
// parent with a zero partial: the sweep then needs no branch, and its dead
// write lands on a slot already read (a shared sink would chain every unary
// entry of the sweep through one memory location).
template <class T>
struct tape_entry {
    std::int32_t a, b;
    T da, db;
};

template <class T>
class reverse_tape {
public:
    static reverse_tape& of_this_thread() {
        thread_local reverse_tape tape;
        return tape;
    }
    // The tape recording on this thread, if any: a plain pointer, so that each
    // recorded operation reaches it without thread_local's initialisation guard.
    static reverse_tape*& active() {
        thread_local reverse_tape* tape = nullptr;
        return tape;
    }

    // Starts a recording with n independent variables, nodes 1..n.
    void begin(std::size_t n, const char* who) {
        if (active() != nullptr)
            throw invalid_argument(std::string(who) +
                                   ": a reverse-mode gradient was asked for inside another of the same scalar type; "
                                   "expected one at a time per thread");
        if (n + 1 > std::size_t(INT32_MAX))
            throw invalid_argument(std::string(who) + ": " + std::to_string(n) +
                                   " independent variables; expected fewer than 2^31");
        size_ = 0;
        for (std::size_t i = 0; i <= n; ++i) record(0, T(0));
        active() = this;
    }
    std::int32_t record(std::int32_t a, T da) {
        if (size_ == entries_.size()) [[unlikely]]
            grow();
        entries_[size_] = {a, std::int32_t(size_), da, T(0)};
        return std::int32_t(size_++);
    }
    std::int32_t record(std::int32_t a, T da, std::int32_t b, T db) {
        if (a == b) return record(a, da + db);
        if (size_ == entries_.size()) [[unlikely]]
            grow();
        entries_[size_] = {a, b, da, db};
        return std::int32_t(size_++);
    }
    // Sweeps backwards from `output` and ends the recording; the adjoint of
    // input i (0-based) is then input_adjoint(i).
    void sweep(std::int32_t output) {
        active() = nullptr;
        adjoints_.assign(size_, T(0));
        if (output > 0) adjoints_[std::size_t(output)] = T(1);
        const tape_entry<T>* e = entries_.data();
        T* adj = adjoints_.data();
        for (std::size_t i = size_; i-- > 1;) {
            const T g = adj[i];
            adj[e[i].a] += e[i].da * g;
            adj[e[i].b] += e[i].db * g;
        }
    }
    void abandon() { active() = nullptr; }
    const T& input_adjoint(std::size_t i) const { return adjoints_[i + 1]; }
    std::size_t size() const { return size_; }

private:
    void grow() {
        if (entries_.size() >= std::size_t(INT32_MAX))
            throw invalid_argument("reverse mode: the function recorded more than 2^31 operations; expected fewer");
        entries_.resize(std::max<std::size_t>(1024, 2 * entries_.size()));
    }
    std::vector<tape_entry<T>> entries_;
    std::vector<T> adjoints_;
    std::size_t size_ = 0;
};
}  // namespace detail

// A number on the tape: `node` is the operation that made it, 0 for a constant.
template <class T>
struct taped {
    static_assert(std::is_floating_point_v<T>, "sympl::taped records plain floating-point operations");
    T value{};
    std::int32_t node = 0;

    taped() = default;
    template <class U>
        requires std::is_arithmetic_v<U>
    taped(U v) : value(static_cast<T>(v)) {}
    taped(T v, std::int32_t n) : value(v), node(n) {}

    // Never a plain number silently: that would cut the derivative's path.
    operator T() const {
        static_assert(sizeof(T) == 0,
                      "sympl::taped: a std:: math function was called on a taped number (e.g. std::sqrt(x)), "
                      "which would drop its derivatives; write `using std::sqrt; sqrt(x)` so that its overload is found");
        return value;
    }

    taped& operator+=(const taped& o) { return *this = *this + o; }
    taped& operator-=(const taped& o) { return *this = *this - o; }
    taped& operator*=(const taped& o) { return *this = *this * o; }
    taped& operator/=(const taped& o) { return *this = *this / o; }
};

namespace detail {
template <class T>
reverse_tape<T>& tape() { return *reverse_tape<T>::active(); }
// f(a) with f'(a) given; a constant stays off the tape.
template <class T>
taped<T> unary(const taped<T>& a, T f, T dfda) {
    if (a.node == 0) return {f, 0};
    return {f, tape<T>().record(a.node, dfda)};
}
template <class T>
taped<T> binary(const taped<T>& a, const taped<T>& b, T f, T dfda, T dfdb) {
    if (a.node == 0) return unary(b, f, dfdb);
    if (b.node == 0) return {f, tape<T>().record(a.node, dfda)};
    return {f, tape<T>().record(a.node, dfda, b.node, dfdb)};
}
}  // namespace detail

template <class U, class T>
concept taped_operand = std::is_arithmetic_v<U>;

// Adding a constant keeps the node: d(a + c)/da = 1, so no entry is needed.
template <class T> taped<T> operator+(const taped<T>& a, const taped<T>& b) {
    if (b.node == 0) return {a.value + b.value, a.node};
    if (a.node == 0) return {a.value + b.value, b.node};
    return {a.value + b.value, detail::tape<T>().record(a.node, T(1), b.node, T(1))};
}
template <class T> taped<T> operator-(const taped<T>& a, const taped<T>& b) {
    if (b.node == 0) return {a.value - b.value, a.node};
    return detail::binary(a, b, a.value - b.value, T(1), T(-1));
}
template <class T> taped<T> operator*(const taped<T>& a, const taped<T>& b) {
    return detail::binary(a, b, a.value * b.value, b.value, a.value);
}
template <class T> taped<T> operator/(const taped<T>& a, const taped<T>& b) {
    const T inv = T(1) / b.value, q = a.value * inv;
    return detail::binary(a, b, q, inv, -q * inv);
}
template <class T> taped<T> operator+(const taped<T>& a) { return a; }
template <class T> taped<T> operator-(const taped<T>& a) { return detail::unary(a, -a.value, T(-1)); }

template <class T, class U> requires taped_operand<U, T>
taped<T> operator+(const taped<T>& a, U c) { return {a.value + T(c), a.node}; }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator+(U c, const taped<T>& a) { return {T(c) + a.value, a.node}; }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator-(const taped<T>& a, U c) { return {a.value - T(c), a.node}; }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator-(U c, const taped<T>& a) { return detail::unary(a, T(c) - a.value, T(-1)); }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator*(const taped<T>& a, U c) { return detail::unary(a, a.value * T(c), T(c)); }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator*(U c, const taped<T>& a) { return detail::unary(a, T(c) * a.value, T(c)); }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator/(const taped<T>& a, U c) { return detail::unary(a, a.value / T(c), T(1) / T(c)); }
template <class T, class U> requires taped_operand<U, T>
taped<T> operator/(U c, const taped<T>& a) {
    const T q = T(c) / a.value;
    return detail::unary(a, q, -q / a.value);
}

// Comparisons look at the value only (branches in V(q) follow the primal path).
template <class T> bool operator==(const taped<T>& a, const taped<T>& b) { return a.value == b.value; }
template <class T> auto operator<=>(const taped<T>& a, const taped<T>& b) { return a.value <=> b.value; }
template <class T, class U> requires taped_operand<U, T>
bool operator==(const taped<T>& a, U c) { return a.value == T(c); }
template <class T, class U> requires taped_operand<U, T>
auto operator<=>(const taped<T>& a, U c) { return a.value <=> T(c); }

// Elementary functions, found by argument-dependent lookup (also by Eigen).
template <class T> taped<T> sqrt(const taped<T>& a) {
    using std::sqrt;
    const T s = sqrt(a.value);
    return detail::unary(a, s, T(0.5) / s);
}
template <class T> taped<T> cbrt(const taped<T>& a) {
    using std::cbrt;
    const T c = cbrt(a.value);
    return detail::unary(a, c, T(1) / (T(3) * c * c));
}
template <class T> taped<T> exp(const taped<T>& a) {
    using std::exp;
    const T e = exp(a.value);
    return detail::unary(a, e, e);
}
template <class T> taped<T> expm1(const taped<T>& a) {
    using std::expm1; using std::exp;
    return detail::unary(a, expm1(a.value), exp(a.value));
}
template <class T> taped<T> log(const taped<T>& a) {
    using std::log;
    return detail::unary(a, log(a.value), T(1) / a.value);
}
template <class T> taped<T> log1p(const taped<T>& a) {
    using std::log1p;
    return detail::unary(a, log1p(a.value), T(1) / (T(1) + a.value));
}
template <class T> taped<T> sin(const taped<T>& a) {
    using std::sin; using std::cos;
    return detail::unary(a, sin(a.value), cos(a.value));
}
template <class T> taped<T> cos(const taped<T>& a) {
    using std::sin; using std::cos;
    return detail::unary(a, cos(a.value), -sin(a.value));
}
template <class T> taped<T> tan(const taped<T>& a) {
    using std::tan;
    const T t = tan(a.value);
    return detail::unary(a, t, T(1) + t * t);
}
template <class T> taped<T> sinh(const taped<T>& a) {
    using std::sinh; using std::cosh;
    return detail::unary(a, sinh(a.value), cosh(a.value));
}
template <class T> taped<T> cosh(const taped<T>& a) {
    using std::sinh; using std::cosh;
    return detail::unary(a, cosh(a.value), sinh(a.value));
}
template <class T> taped<T> tanh(const taped<T>& a) {
    using std::tanh;
    const T t = tanh(a.value);
    return detail::unary(a, t, T(1) - t * t);
}
template <class T> taped<T> atan(const taped<T>& a) {
    using std::atan;
    return detail::unary(a, atan(a.value), T(1) / (T(1) + a.value * a.value));
}
template <class T> taped<T> asin(const taped<T>& a) {
    using std::asin; using std::sqrt;
    return detail::unary(a, asin(a.value), T(1) / sqrt(T(1) - a.value * a.value));
}
template <class T> taped<T> acos(const taped<T>& a) {
    using std::acos; using std::sqrt;
    return detail::unary(a, acos(a.value), T(-1) / sqrt(T(1) - a.value * a.value));
}
template <class T> taped<T> abs(const taped<T>& a) { return a.value < T(0) ? -a : a; }
template <class T> taped<T> fabs(const taped<T>& a) { return abs(a); }
template <class T> taped<T> abs2(const taped<T>& a) { return detail::unary(a, a.value * a.value, T(2) * a.value); }
template <class T> taped<T> atan2(const taped<T>& y, const taped<T>& x) {
    using std::atan2;
    const T r2 = x.value * x.value + y.value * y.value;
    return detail::binary(y, x, atan2(y.value, x.value), x.value / r2, -y.value / r2);
}
template <class T> taped<T> hypot(const taped<T>& x, const taped<T>& y) {
    using std::hypot;
    const T h = hypot(x.value, y.value);
    return detail::binary(x, y, h, x.value / h, y.value / h);
}
// a^e for a constant exponent: one entry, finite for a <= 0 with an integer e.
template <class T, class U> requires taped_operand<U, T>
taped<T> pow(const taped<T>& a, U e) {
    using std::pow;
    const T pm1 = pow(a.value, T(e) - T(1));
    return detail::unary(a, pm1 * a.value, T(e) * pm1);
}
template <class T> taped<T> pow(const taped<T>& a, const taped<T>& e) {
    using std::pow; using std::log;
    if (e.node == 0) return pow(a, e.value);
    const T pm1 = pow(a.value, e.value - T(1)), v = pm1 * a.value;
    return detail::binary(a, e, v, e.value * pm1, v * log(a.value));
}
template <class T, class U> requires taped_operand<U, T>
taped<T> pow(U base, const taped<T>& e) { return pow(taped<T>(base), e); }
template <class T> bool isfinite(const taped<T>& a) {
    using std::isfinite;
    return isfinite(a.value);
}

// out = d fn / d x by one recording and one backward sweep. The tape and the
// adjoint workspace are this thread's and keep their memory (no allocation once
// warm). If fn throws, the recording is abandoned and the exception goes on.
template <class Vec, class Fn>
void reverse_gradient(const Fn& fn, const Vec& x, Vec& out) {
    using T = typename Vec::Scalar;
    using A = taped<T>;
    using AVec = Eigen::Matrix<A, Vec::RowsAtCompileTime, 1>;
    thread_local AVec xa;
    auto& tape = detail::reverse_tape<T>::of_this_thread();
    const Eigen::Index n = x.size();
    tape.begin(std::size_t(n), "reverse_gradient");
    if (xa.size() != n) xa.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) xa[i] = A(x[i], std::int32_t(i + 1));
    A y;
    try {
        y = fn(xa);
    } catch (...) {
        tape.abandon();
        throw;
    }
    tape.sweep(y.node);
    if (out.size() != n) out.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) out[i] = tape.input_adjoint(std::size_t(i));
}

}  // namespace sympl

// Eigen needs to know how a taped number behaves as a matrix scalar.
namespace Eigen {
template <class T>
struct NumTraits<sympl::taped<T>> : NumTraits<T> {
    using Real = sympl::taped<T>;
    using NonInteger = sympl::taped<T>;
    using Nested = sympl::taped<T>;
    using Literal = sympl::taped<T>;
    enum {
        IsComplex = 0,
        IsInteger = 0,
        IsSigned = 1,
        RequireInitialization = 1,
        ReadCost = 2 * NumTraits<T>::ReadCost,
        AddCost = 4 * NumTraits<T>::AddCost,
        MulCost = 4 * NumTraits<T>::MulCost
    };
    static Real epsilon() { return Real(NumTraits<T>::epsilon()); }
    static Real dummy_precision() { return Real(NumTraits<T>::dummy_precision()); }
    static Real highest() { return Real(NumTraits<T>::highest()); }
    static Real lowest() { return Real(NumTraits<T>::lowest()); }
    static int digits10() { return NumTraits<T>::digits10(); }
};
template <class T, class U>
    requires std::is_arithmetic_v<U>
struct ScalarBinaryOpTraits<sympl::taped<T>, U, internal::scalar_product_op<sympl::taped<T>, U>> {
    using ReturnType = sympl::taped<T>;
};
template <class T, class U>
    requires std::is_arithmetic_v<U>
struct ScalarBinaryOpTraits<U, sympl::taped<T>, internal::scalar_product_op<U, sympl::taped<T>>> {
    using ReturnType = sympl::taped<T>;
};
template <class T, class U>
    requires std::is_arithmetic_v<U>
struct ScalarBinaryOpTraits<sympl::taped<T>, U, internal::scalar_quotient_op<sympl::taped<T>, U>> {
    using ReturnType = sympl::taped<T>;
};
}  // namespace Eigen
