#pragma once
// Reverse-mode automatic differentiation: a taped number is a value and the
// nodes of this thread's tape (reverse_tape.hpp) it was computed from. One
// evaluation of f records its statements; one backward sweep then gives the
// whole gradient, at a cost that is a small multiple of evaluating f whatever
// the dimension (Griewank & Walther, Evaluating Derivatives, 2nd ed. 2008,
// ch. 3). Arithmetic on taped numbers builds expressions that are recorded as
// one statement when assigned to a taped number (Hogan 2014, ACM TOMS 40:26),
// so `v += r2 / 2 + r2 * r2 * k` is one statement with its partials, not four.
// Forward mode (dual.hpp) costs n/8 evaluations for n inputs: hamiltonian.hpp
// uses this file for large or dynamic-size states, dual numbers below.
//
// Write generic code as for dual numbers (`using std::sqrt; sqrt(x)`); declare
// intermediate results with the scalar type (`const S r = a - b;`) rather than
// `auto`, and give both branches of `c ? x : y` that type.
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "reverse_tape.hpp"

namespace sympl {

template <class E>
concept reverse_expression = requires { typename E::reverse_value; };
template <class U>
concept plain_number = std::is_arithmetic_v<U>;

// A value on the tape: to first order, `scale` times its node's value plus
// `scale2` times node2's, where a node is an input or a statement that was
// recorded (node 0 stands for constants; node2 0 for none). A value computed
// from one pair of nodes (r = a - b, r * r, sqrt(r)) records no statement: it
// keeps the nodes with their derivatives as scales, and each use passes them
// on (the chain rule taken at recording time; reverse_tape.hpp). The FPU chain's
// bond r = q[i] - q[i-1] and its square are such values: a bond costs one
// statement of three edges (the sum, and the bond's two ends).
template <class T>
struct taped {
    static_assert(std::is_floating_point_v<T>, "sympl::taped records plain floating-point arithmetic");
    using reverse_value = T;
    static constexpr std::size_t leaves = 2;  // nodes an expression of it emits, at most
    T value{};
    T scale = 1;
    T scale2 = 0;
    std::int32_t node = 0;
    std::int32_t node2 = 0;

    taped() = default;
    template <plain_number U>
    taped(U v) : value(static_cast<T>(v)) {}
    taped(T v, std::int32_t n) : value(v), node(n) {}
    // An expression of three or more distinct nodes becomes one statement: its
    // partials with respect to the nodes it was computed from.
    template <reverse_expression E>
        requires(!std::same_as<E, taped> && std::same_as<typename E::reverse_value, T>)
    taped(const E& e) : value(e.value) {
        if constexpr (E::leaves <= 2) {
            typename detail::reverse_tape<T>::writer w{nullptr, 0};
            e.emit(w, T(1));
            detail::reverse_tape<T>::keep_held(w, *this);
        } else {
            auto* tape = detail::reverse_tape<T>::active();
            if (tape == nullptr) return;
            auto w = tape->open_statement(E::leaves);
            e.emit(w, T(1));
            tape->close_statement(w, *this);
        }
    }
    template <class Tape>
    void emit(Tape& tape, T multiplier) const {
        tape.emit(node, multiplier * scale, node2, multiplier * scale2);
    }

    // Never a plain number silently: that would cut the derivative's path.
    operator T() const {
        static_assert(sizeof(T) == 0,
                      "sympl::taped: a std:: math function was called on a taped number (e.g. std::sqrt(x)), which "
                      "would drop its derivatives; write `using std::sqrt; sqrt(x)` so that its overload is found");
        return value;
    }

    template <class X> taped& operator+=(const X& x) { return *this = *this + x; }
    template <class X> taped& operator-=(const X& x) { return *this = *this - x; }
    template <class X> taped& operator*=(const X& x) { return *this = *this * x; }
    template <class X> taped& operator/=(const X& x) { return *this = *this / x; }
};

// ---- expressions: a value, and how its partials pass to what it was made of ----
// Operands are held by value (a taped number is a value and an index), so an
// expression never refers to a temporary that is gone.
template <class A, class B>
struct reverse_sum {
    using reverse_value = typename A::reverse_value;
    static constexpr std::size_t leaves = A::leaves + B::leaves;
    A a; B b; reverse_value value;
    template <class Tape> void emit(Tape& t, reverse_value m) const { a.emit(t, m); b.emit(t, m); }
};
template <class A, class B>
struct reverse_difference {
    using reverse_value = typename A::reverse_value;
    static constexpr std::size_t leaves = A::leaves + B::leaves;
    A a; B b; reverse_value value;
    template <class Tape> void emit(Tape& t, reverse_value m) const { a.emit(t, m); b.emit(t, -m); }
};
template <class A, class B>
struct reverse_product {
    using reverse_value = typename A::reverse_value;
    static constexpr std::size_t leaves = A::leaves + B::leaves;
    A a; B b; reverse_value value;
    template <class Tape> void emit(Tape& t, reverse_value m) const { a.emit(t, m * b.value); b.emit(t, m * a.value); }
};
template <class A, class B>
struct reverse_quotient {
    using reverse_value = typename A::reverse_value;
    static constexpr std::size_t leaves = A::leaves + B::leaves;
    A a; B b; reverse_value value, inverse;  // value = a / b, inverse = 1 / b
    template <class Tape> void emit(Tape& t, reverse_value m) const {
        a.emit(t, m * inverse);
        b.emit(t, -m * value * inverse);
    }
};
// f(a) with f'(a) known: every unary function, and a times or plus a constant.
template <class A>
struct reverse_unary {
    using reverse_value = typename A::reverse_value;
    static constexpr std::size_t leaves = A::leaves;
    A a; reverse_value value, derivative;
    template <class Tape> void emit(Tape& t, reverse_value m) const { a.emit(t, m * derivative); }
};
template <class A, class B>
struct reverse_binary {
    using reverse_value = typename A::reverse_value;
    static constexpr std::size_t leaves = A::leaves + B::leaves;
    A a; B b; reverse_value value, da, db;
    template <class Tape> void emit(Tape& t, reverse_value m) const { a.emit(t, m * da); b.emit(t, m * db); }
};

template <class A, class B>
concept reverse_pair = reverse_expression<A> && reverse_expression<B> &&
                       std::same_as<typename A::reverse_value, typename B::reverse_value>;
template <class E>
using reverse_value_of = typename E::reverse_value;

template <class A, class B> requires reverse_pair<A, B>
reverse_sum<A, B> operator+(const A& a, const B& b) { return {a, b, a.value + b.value}; }
template <class A, class B> requires reverse_pair<A, B>
reverse_difference<A, B> operator-(const A& a, const B& b) { return {a, b, a.value - b.value}; }
template <class A, class B> requires reverse_pair<A, B>
reverse_product<A, B> operator*(const A& a, const B& b) { return {a, b, a.value * b.value}; }
template <class A, class B> requires reverse_pair<A, B>
reverse_quotient<A, B> operator/(const A& a, const B& b) {
    const auto inverse = 1 / b.value;
    return {a, b, a.value * inverse, inverse};
}
template <reverse_expression A> A operator+(const A& a) { return a; }
template <reverse_expression A> reverse_unary<A> operator-(const A& a) { return {a, -a.value, -1}; }

template <reverse_expression A, plain_number U>
reverse_unary<A> operator+(const A& a, U c) { return {a, a.value + reverse_value_of<A>(c), 1}; }
template <plain_number U, reverse_expression A>
reverse_unary<A> operator+(U c, const A& a) { return {a, reverse_value_of<A>(c) + a.value, 1}; }
template <reverse_expression A, plain_number U>
reverse_unary<A> operator-(const A& a, U c) { return {a, a.value - reverse_value_of<A>(c), 1}; }
template <plain_number U, reverse_expression A>
reverse_unary<A> operator-(U c, const A& a) { return {a, reverse_value_of<A>(c) - a.value, -1}; }
template <reverse_expression A, plain_number U>
reverse_unary<A> operator*(const A& a, U c) {
    const auto k = reverse_value_of<A>(c);
    return {a, a.value * k, k};
}
template <plain_number U, reverse_expression A>
reverse_unary<A> operator*(U c, const A& a) { return a * c; }
template <reverse_expression A, plain_number U>
reverse_unary<A> operator/(const A& a, U c) {
    const auto k = reverse_value_of<A>(c);
    return {a, a.value / k, 1 / k};
}
template <plain_number U, reverse_expression A>
reverse_unary<A> operator/(U c, const A& a) {
    const auto q = reverse_value_of<A>(c) / a.value;
    return {a, q, -q / a.value};
}

// Comparisons look at the value only (branches in V(q) follow the primal path).
template <class X>
constexpr auto reverse_primal(const X& x) {
    if constexpr (reverse_expression<X>) return x.value;
    else return x;
}
template <class A, class B>
concept reverse_comparable = (reverse_expression<A> && (reverse_expression<B> || plain_number<B>)) ||
                             (plain_number<A> && reverse_expression<B>);
template <class A, class B> requires reverse_comparable<A, B>
bool operator==(const A& a, const B& b) { return reverse_primal(a) == reverse_primal(b); }
template <class A, class B> requires reverse_comparable<A, B>
auto operator<=>(const A& a, const B& b) { return reverse_primal(a) <=> reverse_primal(b); }

// ---- elementary functions, found by argument-dependent lookup (also by Eigen) ----
// A function of a compound argument, sqrt(dx * dx + dy * dy + dz * dz), makes
// the argument a taped value first (a statement, if it depends on more than two
// nodes) and keeps the function as its scale. Nesting the whole expression made
// every enclosing expression carry and copy it, and GCC then kept the trees in
// memory: recording the argument first, one more statement and one more edge,
// is the faster (docs/speed.md, "Figures behind choices in the code").
template <reverse_expression A>
auto function_argument(const A& a) {
    if constexpr (A::leaves > 2) return taped<reverse_value_of<A>>(a);
    else return a;
}
#define SYMPL_REVERSE_UNARY(name, value_expr, derivative_expr)                          \
    template <reverse_expression A>                                                    \
    auto name(const A& argument) {                                                     \
        using std::sqrt, std::exp, std::log, std::sin, std::cos;                       \
        const auto a = function_argument(argument);                                    \
        const auto x = a.value;                                                        \
        const auto f = value_expr;                                                     \
        return reverse_unary<std::remove_const_t<decltype(a)>>{                        \
            a, f, static_cast<reverse_value_of<A>>(derivative_expr)};                  \
    }
SYMPL_REVERSE_UNARY(sqrt, sqrt(x), 1 / (2 * f))
SYMPL_REVERSE_UNARY(cbrt, std::cbrt(x), 1 / (3 * f * f))
SYMPL_REVERSE_UNARY(exp, exp(x), f)
SYMPL_REVERSE_UNARY(expm1, std::expm1(x), exp(x))
SYMPL_REVERSE_UNARY(exp2, std::exp2(x), f * log(decltype(x)(2)))
SYMPL_REVERSE_UNARY(log, log(x), 1 / x)
SYMPL_REVERSE_UNARY(log1p, std::log1p(x), 1 / (1 + x))
SYMPL_REVERSE_UNARY(log2, std::log2(x), 1 / (x * log(decltype(x)(2))))
SYMPL_REVERSE_UNARY(log10, std::log10(x), 1 / (x * log(decltype(x)(10))))
SYMPL_REVERSE_UNARY(sin, sin(x), cos(x))
SYMPL_REVERSE_UNARY(cos, cos(x), -sin(x))
SYMPL_REVERSE_UNARY(tan, std::tan(x), 1 + f * f)
SYMPL_REVERSE_UNARY(sinh, std::sinh(x), std::cosh(x))
SYMPL_REVERSE_UNARY(cosh, std::cosh(x), std::sinh(x))
SYMPL_REVERSE_UNARY(tanh, std::tanh(x), 1 - f * f)
SYMPL_REVERSE_UNARY(asin, std::asin(x), 1 / sqrt(1 - x * x))
SYMPL_REVERSE_UNARY(acos, std::acos(x), -1 / sqrt(1 - x * x))
SYMPL_REVERSE_UNARY(atan, std::atan(x), 1 / (1 + x * x))
SYMPL_REVERSE_UNARY(asinh, std::asinh(x), 1 / sqrt(x * x + 1))
SYMPL_REVERSE_UNARY(acosh, std::acosh(x), 1 / sqrt(x * x - 1))
SYMPL_REVERSE_UNARY(atanh, std::atanh(x), 1 / (1 - x * x))
SYMPL_REVERSE_UNARY(abs, std::abs(x), x < 0 ? -1 : 1)
SYMPL_REVERSE_UNARY(fabs, std::abs(x), x < 0 ? -1 : 1)
SYMPL_REVERSE_UNARY(abs2, x * x, 2 * x)
#undef SYMPL_REVERSE_UNARY

template <class A, class B> requires reverse_pair<A, B>
reverse_binary<A, B> atan2(const A& y, const B& x) {
    const auto r2 = x.value * x.value + y.value * y.value;
    return {y, x, std::atan2(y.value, x.value), x.value / r2, -y.value / r2};
}
template <class A, class B> requires reverse_pair<A, B>
reverse_binary<A, B> hypot(const A& x, const B& y) {
    const auto h = std::hypot(x.value, y.value);
    return {x, y, h, x.value / h, y.value / h};
}
// a^e for a constant exponent: finite for a <= 0 with an integer e.
template <reverse_expression A, plain_number U>
auto pow(const A& argument, U e) {
    using T = reverse_value_of<A>;
    const auto a = function_argument(argument);
    const T pm1 = std::pow(a.value, T(e) - T(1));
    return reverse_unary<std::remove_const_t<decltype(a)>>{a, pm1 * a.value, T(e) * pm1};
}
template <class A, class B> requires reverse_pair<A, B>
reverse_binary<A, B> pow(const A& a, const B& e) {
    const auto pm1 = std::pow(a.value, e.value - 1), v = pm1 * a.value;
    return {a, e, v, e.value * pm1, v * std::log(a.value)};
}
template <plain_number U, reverse_expression A>
reverse_unary<A> pow(U base, const A& e) {
    using T = reverse_value_of<A>;
    const T v = std::pow(T(base), e.value);
    return {e, v, v * std::log(T(base))};
}
// Mixed with a constant: atan2 and hypot through a taped constant.
template <reverse_expression A, plain_number U>
auto atan2(const A& y, U x) { return atan2(y, taped<reverse_value_of<A>>(x)); }
template <plain_number U, reverse_expression A>
auto atan2(U y, const A& x) { return atan2(taped<reverse_value_of<A>>(y), x); }
template <reverse_expression A, plain_number U>
auto hypot(const A& x, U y) { return hypot(x, taped<reverse_value_of<A>>(y)); }
template <plain_number U, reverse_expression A>
auto hypot(U x, const A& y) { return hypot(taped<reverse_value_of<A>>(x), y); }
template <reverse_expression A>
bool isfinite(const A& a) { return std::isfinite(a.value); }

// out = factor * d fn / d x by one recording and one backward sweep (the
// factor as the output's adjoint: a force is -dV/dq without a pass of its own). The tape and the
// workspace are this thread's and keep their memory (no allocation once warm).
// If fn throws, the recording is abandoned and the exception goes on.
template <class Vec, class Fn>
void reverse_gradient(const Fn& fn, const Vec& x, Vec& out, typename Vec::Scalar factor = 1) {
    using T = typename Vec::Scalar;
    using A = taped<T>;
    using AVec = Eigen::Matrix<A, Vec::RowsAtCompileTime, 1>;
    // Input i is node i + 1 at every call: only the values change.
    thread_local AVec xa;
    thread_local Eigen::Index numbered = -1;  // the size xa's nodes were written for
    auto& tape = detail::reverse_tape<T>::of_this_thread();
    const Eigen::Index n = x.size();
    tape.begin(std::size_t(n), "reverse_gradient");
    if (numbered != n) {
        xa.resize(n);
        for (Eigen::Index i = 0; i < n; ++i) xa[i] = A(T(0), std::int32_t(i + 1));
        numbered = n;
    }
    for (Eigen::Index i = 0; i < n; ++i) xa[i].value = x[i];
    A y;
    try {
        y = fn(std::as_const(xa));  // read only: the inputs' nodes are written once per size
    } catch (...) {
        tape.abandon();
        throw;
    }
    tape.sweep(y.node, factor * y.scale, y.node2, factor * y.scale2);
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
