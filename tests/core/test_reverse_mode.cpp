// Reverse-mode gradients: every elementary function against its derivative,
// every ready-made system's potential against its analytic force, the tape's
// length linear in the dimension, and misuse refused.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <sympl/core/reverse_mode.hpp>
#include <sympl/core/error.hpp>
#include <sympl/hamiltonians/charged_particle.hpp>
#include <sympl/hamiltonians/double_pendulum.hpp>
#include <sympl/hamiltonians/double_well.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/morse.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/product_hamiltonian.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>
#include <sympl/hamiltonians/stiff_fpu.hpp>
#include <sympl/hamiltonians/toda.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

namespace test_core_test_reverse_mode {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using Vec = Eigen::VectorXd;

namespace {
constexpr double eps = 2.220446049250313e-16;

// -dV/dq by one recording and one sweep, against the system's analytic force.
template <class H>
void check_force(const H& h, const Vec& q) {
    Vec g, f;
    reverse_gradient([&h](const auto& x) { return h.potential(x); }, q, g);
    h.force(q, f);
    CAPTURE(q.size());
    CHECK((-g - f).norm() <= 1e-14 * f.norm());
}

// dH/dq and dH/dp of a Hamiltonian that does not split (energy(q, p)) by
// reverse mode, each with the other half of the state held fixed, against the
// system's analytic gradients.
template <class H>
void check_general(const H& h, const Vec& q, const Vec& p) {
    Vec gq, gp, aq, ap;
    reverse_gradient(
        [&h, &p](const auto& x) {
            using X = std::decay_t<decltype(x)>;
            return h.energy(x, X(p.template cast<typename X::Scalar>()));
        },
        q, gq);
    reverse_gradient(
        [&h, &q](const auto& x) {
            using X = std::decay_t<decltype(x)>;
            return h.energy(X(q.template cast<typename X::Scalar>()), x);
        },
        p, gp);
    h.dH_dq(q, p, aq);
    h.dH_dp(q, p, ap);
    CHECK((gq - aq).norm() <= 1e-14 * aq.norm());
    CHECK((gp - ap).norm() <= 1e-14 * ap.norm());
}

Vec wave(Eigen::Index n, double k, double amplitude) {
    Vec v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = amplitude * std::sin(k * double(i + 1));
    return v;
}
}  // namespace

TEST_CASE("reverse mode: each elementary function's derivative to rounding") {
    // f(x0, x1) = g(x0) * x1: the x0-derivative is g'(x0) x1, the x1-derivative g(x0).
    auto check = [](auto g, double x, double dg) {
        Vec in(2), out;
        in << x, 1.5;
        reverse_gradient([&g](const auto& v) { return g(v[0]) * v[1]; }, in, out);
        CHECK(std::abs(out[0] - 1.5 * dg) <= 8 * eps * std::abs(1.5 * dg));
    };
    const double x = 0.37;
    check([](const auto& a) { using std::sqrt; return sqrt(a); }, x, 0.5 / std::sqrt(x));
    check([](const auto& a) { using std::cbrt; return cbrt(a); }, x, 1 / (3 * std::cbrt(x) * std::cbrt(x)));
    check([](const auto& a) { using std::exp; return exp(a); }, x, std::exp(x));
    check([](const auto& a) { using std::expm1; return expm1(a); }, x, std::exp(x));
    check([](const auto& a) { using std::log; return log(a); }, x, 1 / x);
    check([](const auto& a) { using std::log1p; return log1p(a); }, x, 1 / (1 + x));
    check([](const auto& a) { using std::sin; return sin(a); }, x, std::cos(x));
    check([](const auto& a) { using std::cos; return cos(a); }, x, -std::sin(x));
    check([](const auto& a) { using std::tan; return tan(a); }, x, 1 / (std::cos(x) * std::cos(x)));
    check([](const auto& a) { using std::sinh; return sinh(a); }, x, std::cosh(x));
    check([](const auto& a) { using std::cosh; return cosh(a); }, x, std::sinh(x));
    check([](const auto& a) { using std::tanh; return tanh(a); }, x, 1 / (std::cosh(x) * std::cosh(x)));
    check([](const auto& a) { using std::atan; return atan(a); }, x, 1 / (1 + x * x));
    check([](const auto& a) { using std::asin; return asin(a); }, x, 1 / std::sqrt(1 - x * x));
    check([](const auto& a) { using std::acos; return acos(a); }, x, -1 / std::sqrt(1 - x * x));
    check([](const auto& a) { using std::abs; return abs(-a); }, x, 1.0);
    check([](const auto& a) { using std::pow; return pow(a, 3.5); }, x, 3.5 * std::pow(x, 2.5));
    check([](const auto& a) { return 2.0 / a - a / 4.0 + (3.0 - a); }, x, -2 / (x * x) - 0.25 - 1);
    check([](const auto& a) { using std::atan2; return atan2(a, a * a + 1.0); }, x,
          (1 - x * x) / ((x * x + 1) * (x * x + 1) + x * x));
    check([](const auto& a) { using std::hypot; return hypot(a, 2.0 * a); }, x, std::sqrt(5.0));
}

TEST_CASE("reverse mode: a function of a compound argument records the argument once") {
    // f = x2 / sqrt(x0^2 + x1^2 + 1/2): the argument is one statement (its
    // nodes emitted x0, x0, x1, x1 are written x0, x1, x1: reverse_tape.hpp);
    // the quotient is two single nodes, x2 and the argument, kept as a pair.
    Vec in(3), out;
    in << 0.3, -0.7, 1.9;
    reverse_gradient([](const auto& v) { using std::sqrt; return v[2] / sqrt(v[0] * v[0] + v[1] * v[1] + 0.5); }, in, out);
    const double r2 = 0.3 * 0.3 + 0.7 * 0.7 + 0.5, s = 1 / std::sqrt(r2);
    CHECK(std::abs(out[0] + 1.9 * 0.3 * s / r2) <= 8 * eps * 1.9 * 0.3 * s / r2);
    CHECK(std::abs(out[1] - 1.9 * 0.7 * s / r2) <= 8 * eps * 1.9 * 0.7 * s / r2);
    CHECK(std::abs(out[2] - s) <= 4 * eps * s);
    const auto& tape = detail::reverse_tape<double>::of_this_thread();
    CHECK(tape.statements() == 1 + 3 + 1);  // the constants' node, the inputs, one statement
    CHECK(tape.operations() == 3);
}

TEST_CASE("reverse mode: a value of two nodes records nothing, and nodes met again later add up") {
    // 3 x0 - 2 x1 depends on two nodes: no statement at all, the output is the
    // pair itself and the sweep seeds both.
    Vec in(3), out;
    in << 0.3, -0.7, 1.9;
    reverse_gradient([](const auto& v) { return 3.0 * v[0] - 2.0 * v[1]; }, in, out);
    const auto& tape = detail::reverse_tape<double>::of_this_thread();
    CHECK(tape.statements() == 1 + 3);
    CHECK(tape.operations() == 0);
    CHECK(out[0] == 3.0);
    CHECK(out[1] == -2.0);
    CHECK(out[2] == 0.0);
    // Each input twice, more than two nodes: a statement whose edges name a
    // node more than once, summed by the sweep.
    reverse_gradient([](const auto& v) { return v[0] * v[1] + v[1] * v[2] + v[2] * v[0]; }, in, out);
    CHECK(std::abs(out[0] - (in[1] + in[2])) <= 4 * eps * std::abs(in[1] + in[2]));
    CHECK(std::abs(out[1] - (in[0] + in[2])) <= 4 * eps * std::abs(in[0] + in[2]));
    CHECK(std::abs(out[2] - (in[1] + in[0])) <= 4 * eps * std::abs(in[1] + in[0]));
    // A pair used in two statements, and a running sum swept through the
    // adjoint the previous edge wrote: d/dx of sum_k (x0 - x1)^k x2, k = 1..4.
    reverse_gradient(
        [](const auto& v) {
            using S = typename std::decay_t<decltype(v)>::Scalar;
            const S d = v[0] - v[1];
            S sum(0), power(1);
            for (int k = 1; k <= 4; ++k) {
                power = power * d;
                sum += power * v[2];
            }
            return sum;
        },
        in, out);
    const double d = in[0] - in[1], dsum = 1 + 2 * d + 3 * d * d + 4 * d * d * d, sum = d + d * d + d * d * d + d * d * d * d;
    CHECK(std::abs(out[0] - dsum * in[2]) <= 16 * eps * std::abs(dsum * in[2]));
    CHECK(std::abs(out[1] + dsum * in[2]) <= 16 * eps * std::abs(dsum * in[2]));
    CHECK(std::abs(out[2] - sum) <= 16 * eps * std::abs(sum));
}

TEST_CASE("reverse mode: a variable exponent, and branches follow the value") {
    Vec in(2), out;
    in << 1.7, 2.3;
    reverse_gradient([](const auto& v) { using std::pow; return pow(v[0], v[1]); }, in, out);
    CHECK(std::abs(out[0] - 2.3 * std::pow(1.7, 1.3)) <= 8 * eps * out[0]);
    CHECK(std::abs(out[1] - std::pow(1.7, 2.3) * std::log(1.7)) <= 8 * eps * out[1]);
    reverse_gradient(
        [](const auto& v) {
            using S = typename std::decay_t<decltype(v)>::Scalar;  // both branches one type (reverse_mode.hpp)
            return v[0] > v[1] ? S(v[0] * v[0]) : S(v[1] * v[1] * v[1]);
        },
        in, out);
    CHECK(out[0] == 0.0);
    CHECK(std::abs(out[1] - 3 * 2.3 * 2.3) <= 4 * eps * out[1]);
}

TEST_CASE("reverse mode: the potential of every ready-made system against its analytic force") {
    check_force(hamiltonians::harmonic_oscillator{2.0, 1.5}, wave(3, 0.9, 1.2));
    check_force(hamiltonians::pendulum{1.5, 0.8, 9.81}, wave(1, 2.1, 1.0));
    check_force(hamiltonians::kepler{}, wave(2, 0.7, 0.9));
    check_force(hamiltonians::kepler{}, wave(3, 0.7, 0.9));
    check_force(hamiltonians::relativistic_pendulum{2.0, 1.5, 0.7}, wave(3, 1.1, 2.0));
    check_force(hamiltonians::two_particle_spring{1.5, 2.5}, wave(4, 0.6, 1.0));
    check_force(hamiltonians::henon_heiles{}, wave(2, 0.5, 0.4));
    check_force(hamiltonians::stiff_fpu{}, wave(6, 0.8, 0.4));
    check_force(hamiltonians::morse{2.0, 1.5, 0.8, 0.2}, wave(3, 0.8, 1.0));
    check_force(hamiltonians::double_well{0.7}, wave(3, 0.8, 1.3));
    check_force(hamiltonians::toda{}, wave(3, 0.8, 1.3));
    const hamiltonians::outer_solar_system s{};
    check_force(s, Vec(s.initial_state().q));
    for (Eigen::Index n : {21, 1000, 100000}) check_force(hamiltonians::fpu_beta{0.8}, wave(n, 0.7, 0.5));
}

TEST_CASE("reverse mode: dH/dq and dH/dp of every ready-made general Hamiltonian against its analytic ones") {
    // damped_driven_oscillator is given by its acceleration (Newton's form):
    // it has no potential or energy to differentiate.
    check_general(hamiltonians::charged_particle{1.3, 0.9, 1.7, 1.2, 0.4}, wave(2, 0.7, 0.8), wave(2, 1.3, 0.6));
    check_general(hamiltonians::double_pendulum{1.0, 1.4, 0.8, 1.1, 9.81}, wave(2, 0.7, 0.8), wave(2, 1.3, 0.6));
    check_general(hamiltonians::product_hamiltonian{}, wave(3, 0.7, 0.8), wave(3, 1.3, 0.6));
    check_general(hamiltonians::product_hamiltonian{}, wave(40, 0.7, 0.8), wave(40, 1.3, 0.6));
}

TEST_CASE("reverse mode: one recording per gradient, its length linear in the dimension") {
    // The cost claim behind reverse mode: the tape grows as the number of
    // statements of one evaluation of V, never as n evaluations (forward
    // mode's cost). fpu_beta::potential assigns three values per bond (r, r2
    // and the sum), but r = q[i] - q[i-1] and r2 = r * r depend on two nodes
    // and are kept as that pair with their partials: one statement per bond.
    auto& tape = detail::reverse_tape<double>::of_this_thread();
    auto per_particle = [&](Eigen::Index n) {
        Vec g;
        reverse_gradient([](const auto& x) { return hamiltonians::fpu_beta{1.0}.potential(x); }, wave(n, 0.3, 0.1), g);
        return std::pair{double(tape.statements()) / double(n), double(tape.operations()) / double(n)};
    };
    const auto [statements_small, operations_small] = per_particle(100);
    const auto [statements_large, operations_large] = per_particle(100000);
    CHECK(statements_large == doctest::Approx(1 + 1).epsilon(1e-4));  // the input, and the sum per bond
    // v += r2 / 2 + r2 * r2 * k: v, and the pair (q[i], q[i-1]) three times in a row.
    CHECK(operations_large == doctest::Approx(3).epsilon(1e-4));
    CHECK(std::abs(statements_large - statements_small) <= 3.0 / 100);  // the ends' bonds only
    CHECK(std::abs(operations_large - operations_small) <= 4.0 / 100);
}

TEST_CASE("reverse mode: nesting refused, a throwing function leaves the tape usable") {
    Vec in(2), out;
    in << 1.0, 2.0;
    auto nested = [&](const auto& v) {
        Vec inner;
        reverse_gradient([](const auto& w) { return w[0] * w[1]; }, in, inner);
        return v[0] * v[1];
    };
    CHECK_THROWS_WITH_AS(reverse_gradient(nested, in, out),
                         doctest::Contains("inside another of the same scalar type; expected one at a time"),
                         invalid_argument);
    reverse_gradient([](const auto& v) { return v[0] * v[1]; }, in, out);
    CHECK(out[0] == 2.0);
    CHECK(out[1] == 1.0);
    CHECK_THROWS_AS(reverse_gradient([](const auto& v) -> taped<double> { throw std::runtime_error("V"); return v[0]; },
                                     in, out),
                    std::runtime_error);
    reverse_gradient([](const auto& v) { return v[0] * v[0] * v[1]; }, in, out);
    CHECK(out[0] == 4.0);
    CHECK(out[1] == 1.0);
}

}  // namespace test_core_test_reverse_mode
