#pragma once
// The order a table reaches, measured on the library's own nonlinear test
// problems in 113-bit precision (Boost.Multiprecision), so that roundoff never
// masks the method's own error. Not part of sympl/sympl.hpp: include it when
// measuring orders (it doubles the compile time of a translation unit).
//
// The harmonic oscillator is never used alone: it cannot tell a kick from a
// drift, so a table copied with its roles swapped would pass there. The
// problems are defined here, not taken from hamiltonians/, so that the library
// does not depend on its own examples.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>

#include "../methods/catalog.hpp"
#include "convergence.hpp"
#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../methods/processing.hpp"
#include "../core/splitting_stepper.hpp"
#include "../core/table.hpp"

namespace sympl {

// IEEE-754 binary128 layout in software: 113-bit significand, eps ~ 1e-34.
using quad = boost::multiprecision::number<
    boost::multiprecision::cpp_bin_float<113, boost::multiprecision::digit_base_2, void, std::int16_t, -16382, 16383>,
    boost::multiprecision::et_off>;

namespace detail {
template <class H, class State>
splitting_stepper<H, State> stepper_of(const table& method, const H& h) { return {h, method}; }
template <class H, class State>
processed_stepper<H, State> stepper_of(const processed_method& method, const H& h) { return {h, method}; }
}  // namespace detail

// Measured order of `method` (a table or a processed method, whose output is
// the processed state) on H from x0 over [0, t_end].
template <class Method, class H, int D>
order_measurement measure_order(const Method& method, const H& h, const phase_space<quad, D>& x0, const quad& t_end,
                                const order_options& options = {}) {
    using State = phase_space<quad, D>;
    auto stepper = detail::stepper_of<H, State>(method, h);
    return measure_order(
        [&](std::size_t n) {
            State x = x0;
            stepper.steps(x, t_end / quad(n), n);
            return x;
        },
        static_cast<double>(t_end), options);
}

// The built-in nonlinear test problems.
enum class order_problem {
    pendulum,               // T = p^2/2, V = 1 - cos q: q0 = 1.2, p0 = 0.3, t in [0, 3]
    kepler,                 // T = |p|^2/2, V = -1/|q|, e = 0.5 from pericentre over half a period
    nonquadratic_kinetic,   // T = sqrt(1 + p^2), V = 1 - cos q: q0 = 1.2, p0 = 0.9, t in [0, 3]
};

inline const char* to_string(order_problem p) {
    switch (p) {
        case order_problem::pendulum: return "pendulum";
        case order_problem::kepler: return "kepler";
        case order_problem::nonquadratic_kinetic: return "nonquadratic_kinetic";
    }
    return "?";
}

namespace order_problems {
// Kinetic energies and potentials of the test problems, gradients by autodiff.
// Analytic gradients: autodiff in 113-bit arithmetic would cost 100x more.
struct quadratic_kinetic {
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> const V& velocity(const V& p) const { return p; }
};
struct relativistic_kinetic {
    template <class V> auto kinetic(const V& p) const {
        using std::sqrt;
        return sqrt(1 + p.squaredNorm());
    }
    template <class V> void velocity(const V& p, V& v) const {
        using std::sqrt;
        v = p / sqrt(1 + p.squaredNorm());
    }
};
template <class Kinetic>
struct cosine_potential : Kinetic {
    template <class V> auto potential(const V& q) const {
        using std::cos;
        return 1 - cos(q[0]);
    }
    template <class V> void force(const V& q, V& f) const {
        using std::sin;
        f[0] = -sin(q[0]);
    }
    template <class V> void force_derivative(const V& q, const V& u, V& df) const {  // for force-gradient tables
        using std::cos;
        df[0] = -cos(q[0]) * u[0];
    }
};
struct kepler : quadratic_kinetic {
    template <class V> auto potential(const V& q) const {
        using std::sqrt;
        return -1 / sqrt(q.squaredNorm());
    }
    template <class V> void force(const V& q, V& f) const {
        using std::sqrt;
        const auto r2 = q.squaredNorm();
        f = q * (-1 / (r2 * sqrt(r2)));
    }
    // J_F u = -u / r^3 + 3 (q.u) q / r^5.
    template <class V> void force_derivative(const V& q, const V& u, V& df) const {
        using std::sqrt;
        const auto r2 = q.squaredNorm();
        const auto r3 = r2 * sqrt(r2);
        df = (3 * q.dot(u) / (r2 * r3)) * q - u / r3;
    }
};
}  // namespace order_problems

template <class Method>
    requires std::same_as<Method, table> || std::same_as<Method, processed_method>
order_measurement measure_order(const Method& method, order_problem problem = order_problem::pendulum,
                                const order_options& options = {}) {
    using V1 = Eigen::Matrix<quad, 1, 1>;
    using V2 = Eigen::Matrix<quad, 2, 1>;
    const quad q0 = quad(12) / 10;
    switch (problem) {
        case order_problem::pendulum:
            return measure_order(method, order_problems::cosine_potential<order_problems::quadratic_kinetic>{},
                                 phase_space<quad, 1>(V1(q0), V1(quad(3) / 10)), quad(3), options);
        case order_problem::kepler: {
            // Pericentre of the orbit with semi-major axis 1 and e = 1/2 (Hairer, Lubich & Wanner, GNI eq. I.2.12).
            const quad e = quad(1) / 2;
            return measure_order(method, order_problems::kepler{},
                                 phase_space<quad, 2>(V2(1 - e, quad(0)), V2(quad(0), sqrt((1 + e) / (1 - e)))),
                                 boost::math::constants::pi<quad>(), options);
        }
        case order_problem::nonquadratic_kinetic:
            return measure_order(method, order_problems::cosine_potential<order_problems::relativistic_kinetic>{},
                                 phase_space<quad, 1>(V1(q0), V1(quad(9) / 10)), quad(3), options);
    }
    throw invalid_argument("measure_order: unknown problem");
}

// How accurate a table is for its cost: the max-norm error on the pendulum
// problem of order_problem::pendulum at t = 3 when the method is given
// `forces` force evaluations (n = forces / force_evaluations() steps, at
// least one). Comparing tables at equal cost, not equal dt, is what tells a
// user which one to pick: a 35-stage method takes 35 times longer steps.
// Runs in long double against a 113-bit reference.
inline double error_at_equal_cost(const table& method, std::size_t forces = 300) {
    using L = phase_space<long double, 1>;
    using V1 = Eigen::Matrix<long double, 1, 1>;
    using P = order_problems::cosine_potential<order_problems::quadratic_kinetic>;
    static const L reference = [] {
        using Q1 = Eigen::Matrix<quad, 1, 1>;
        phase_space<quad, 1> x(Q1(quad(12) / 10), Q1(quad(3) / 10));
        splitting_stepper<P, phase_space<quad, 1>> s(P{}, sympl::method("sofroniou_spaletta_10"));
        s.steps(x, quad(3) / 4096, 4096);
        return L(V1(static_cast<long double>(x.q[0])), V1(static_cast<long double>(x.p[0])));
    }();
    const std::size_t n = std::max<std::size_t>(1, forces / method.force_evaluations());
    L x(V1(1.2L), V1(0.3L));
    splitting_stepper<P, L> s(P{}, method);
    s.steps(x, 3.0L / static_cast<long double>(n), n);
    return static_cast<double>(max_difference(x, reference));
}

}  // namespace sympl
