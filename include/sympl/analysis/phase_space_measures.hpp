#pragma once
// Measures of what a symplectic method preserves (Gould & Tobochnik, after eq. 3.73:
// "the sum of the areas formed by the projection of the phase space volume onto
// the planes q_i, p_i ... does not change with time").
//
//  1. carry_loop: a closed loop of initial conditions carried by any flow (a
//     sympl or Odeint stepper run for some steps), refined where neighbouring
//     images drift apart so the polygon stays faithful as the loop stretches;
//     loop_area: its shoelace area in one (q_i, p_i) plane; projected_area_sum:
//     the signed sum over all planes (Poincare's integral invariant).
//  2. flow_jacobian: the exact Jacobian M of the numerical flow map, by running
//     the flow on dual numbers (forward-mode autodiff through the stepper);
//     symplecticity_defect: ||M^T J M - J||_F, zero for a symplectic map.
//  3. finite_difference_jacobian: central differences, to cross-check (2).
//
// A flow is a callable that advances a phase_space state in place; for
// flow_jacobian it must accept states of dual numbers (a generic lambda:
// [&](auto& x) { auto s = make_stepper<std::decay_t<decltype(x)>>(h, t); s.steps(x, dt, n); }).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

template <class S>
using phase_matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;

// J = [[0, I], [-I, 0]] for n degrees of freedom (q first, then p).
template <class S = double>
phase_matrix<S> symplectic_form(Eigen::Index n) {
    phase_matrix<S> J = phase_matrix<S>::Zero(2 * n, 2 * n);
    J.topRightCorner(n, n).setIdentity();
    J.bottomLeftCorner(n, n) = -phase_matrix<S>::Identity(n, n);
    return J;
}

// ||M^T J M - J||_F. Roundoff in M makes it about eps ||M||^2 at best, so
// compare it with M.squaredNorm().
template <class S>
S symplecticity_defect(const phase_matrix<S>& M) {
    if (M.rows() != M.cols() || M.rows() % 2 != 0)
        throw invalid_argument("symplecticity_defect: a " + std::to_string(M.rows()) + "x" + std::to_string(M.cols()) +
                               " matrix; expected a square matrix of even size");
    const phase_matrix<S> J = symplectic_form<S>(M.rows() / 2);
    return (M.transpose() * J * M - J).norm();
}

namespace detail {
// Component k of the stacked (q, p).
template <class State>
auto& component(State& x, Eigen::Index k) {
    return k < x.size() ? x.q[k] : x.p[k - x.size()];
}
}  // namespace detail

// d flow(x) / d x at x0, in chunks of W directions of dual numbers.
template <class Flow, class S, int D>
phase_matrix<S> flow_jacobian(Flow&& flow, const phase_space<S, D>& x0) {
    constexpr int W = (D != Eigen::Dynamic && 2 * D <= 16) ? 2 * D : 8;
    using Dual = dual<S, W>;
    using DState = phase_space<Dual, D>;
    const Eigen::Index n = x0.size(), m = 2 * n;
    phase_matrix<S> M(m, m);
    for (Eigen::Index start = 0; start < m; start += W) {
        DState x(n);
        for (Eigen::Index k = 0; k < m; ++k) detail::component(x, k) = Dual(detail::component(x0, k));
        for (int j = 0; j < W && start + j < m; ++j) detail::component(x, start + j).grad[j] = S(1);
        flow(x);
        if (x.size() != n)
            throw invalid_argument("flow_jacobian: the flow changed the dimension from " + std::to_string(n) + " to " +
                                   std::to_string(x.size()));
        for (Eigen::Index r = 0; r < m; ++r)
            for (int j = 0; j < W && start + j < m; ++j) M(r, start + j) = detail::component(x, r).grad[j];
    }
    return M;
}

// Central differences (flow(x0 + h e_k) - flow(x0 - h e_k)) / 2h with
// h = relative_step * max(1, |x0_k|): error O(h^2) plus roundoff O(eps / h).
template <class Flow, class S, int D>
phase_matrix<S> finite_difference_jacobian(Flow&& flow, const phase_space<S, D>& x0, S relative_step = S(1e-5)) {
    using std::abs;
    using std::max;
    if (!(relative_step > S(0)))
        throw invalid_argument("finite_difference_jacobian: relative_step must be > 0");
    const Eigen::Index n = x0.size(), m = 2 * n;
    phase_matrix<S> M(m, m);
    for (Eigen::Index k = 0; k < m; ++k) {
        const S h = relative_step * max(S(1), abs(detail::component(x0, k)));
        phase_space<S, D> plus = x0, minus = x0;
        detail::component(plus, k) += h;
        detail::component(minus, k) -= h;
        flow(plus);
        flow(minus);
        for (Eigen::Index r = 0; r < m; ++r)
            M(r, k) = (detail::component(plus, r) - detail::component(minus, r)) / (2 * h);
    }
    return M;
}

struct loop_options {
    std::size_t initial_points = 64;
    std::size_t max_points = std::size_t(1) << 14;
    // Neighbouring images farther apart than this (Euclidean, whole phase
    // space) get a point carried from the parameter midway between them.
    double max_gap = 0;
};

template <class State>
struct carried_loop {
    std::vector<double> s;       // loop parameter in [0, 1) of each point, increasing
    std::vector<State> points;   // images under the flow
    bool resolved = false;       // every gap <= max_gap (else max_points was reached)
    double largest_gap = 0;
};

// Carries the loop s -> initial(s), s in [0, 1), through `flow`, refining until
// every gap is at most options.max_gap or options.max_points is reached.
template <class Initial, class Flow>
auto carry_loop(Initial&& initial, Flow&& flow, const loop_options& options) {
    using State = std::decay_t<decltype(initial(0.0))>;
    if (!(options.max_gap > 0) || options.initial_points < 3 || options.max_points < options.initial_points)
        throw invalid_argument("carry_loop: max_gap = " + std::to_string(options.max_gap) + ", initial_points = " +
                               std::to_string(options.initial_points) + ", max_points = " +
                               std::to_string(options.max_points) +
                               "; expected max_gap > 0 and 3 <= initial_points <= max_points");
    const auto image = [&](double s) {
        State x = initial(s);
        flow(x);
        return x;
    };
    const auto gap = [](const State& a, const State& b) {
        return std::sqrt((a.q - b.q).squaredNorm() + (a.p - b.p).squaredNorm());
    };
    carried_loop<State> loop;
    for (std::size_t k = 0; k < options.initial_points; ++k) {
        loop.s.push_back(double(k) / double(options.initial_points));
        loop.points.push_back(image(loop.s.back()));
    }
    bool refined = true;
    while (refined && loop.points.size() < options.max_points) {
        refined = false;
        std::vector<double> s;
        std::vector<State> points;
        const std::size_t n = loop.points.size();
        for (std::size_t k = 0; k < n; ++k) {
            s.push_back(loop.s[k]);
            points.push_back(loop.points[k]);
            const std::size_t next = (k + 1) % n;
            if (points.size() + (n - k) <= options.max_points && gap(loop.points[k], loop.points[next]) > options.max_gap) {
                const double mid = (loop.s[k] + (next == 0 ? 1.0 : loop.s[next])) / 2;
                s.push_back(mid);
                points.push_back(image(mid));
                refined = true;
            }
        }
        loop.s.swap(s);
        loop.points.swap(points);
    }
    loop.largest_gap = 0;
    for (std::size_t k = 0; k < loop.points.size(); ++k)
        loop.largest_gap =
            std::max(loop.largest_gap, double(gap(loop.points[k], loop.points[(k + 1) % loop.points.size()])));
    loop.resolved = loop.largest_gap <= options.max_gap;
    return loop;
}

// Signed shoelace area of the polygon in the (q_i, p_i) plane (counter-clockwise > 0).
template <class State>
double loop_area(const std::vector<State>& points, Eigen::Index plane) {
    double twice = 0;
    const std::size_t n = points.size();
    for (std::size_t k = 0; k < n; ++k) {
        const State& a = points[k];
        const State& b = points[(k + 1) % n];
        if (plane < 0 || plane >= a.size())
            throw invalid_argument("loop_area: plane " + std::to_string(plane) + "; expected 0 <= plane < " +
                                   std::to_string(a.size()));
        twice += double(a.q[plane] * b.p[plane] - b.q[plane] * a.p[plane]);
    }
    return twice / 2;
}

template <class State>
double loop_area(const carried_loop<State>& loop, Eigen::Index plane) {
    return loop_area(loop.points, plane);
}

// How far the polygon's area in the (q_i, p_i) plane may be from that of the
// smooth loop through its points: a curve of curvature kappa bulges beyond a
// chord of length g by an area kappa g^3 / 12, and kappa g is the polygon's
// turning angle there, so the sum over vertices of |turn| * g^2 / 12 (g the
// mean of the two adjacent chords) estimates it. It shrinks as g^2 when the
// loop is refined.
template <class State>
double loop_area_resolution(const std::vector<State>& points, Eigen::Index plane) {
    const std::size_t n = points.size();
    double sum = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const State& a = points[(k + n - 1) % n];
        const State& b = points[k];
        const State& c = points[(k + 1) % n];
        const double ux = double(b.q[plane] - a.q[plane]), uy = double(b.p[plane] - a.p[plane]);
        const double vx = double(c.q[plane] - b.q[plane]), vy = double(c.p[plane] - b.p[plane]);
        const double lu = std::hypot(ux, uy), lv = std::hypot(vx, vy);
        if (lu == 0 || lv == 0) continue;
        const double turn = std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
        const double g = (lu + lv) / 2;
        sum += std::fabs(turn) * g * g / 12;
    }
    return sum;
}

template <class State>
double loop_area_resolution(const carried_loop<State>& loop, Eigen::Index plane) {
    return loop_area_resolution(loop.points, plane);
}

// Sum of the signed projected areas over all planes: the invariant Gould & Tobochnik state after eq. 3.73.
template <class State>
double projected_area_sum(const carried_loop<State>& loop) {
    double sum = 0;
    if (!loop.points.empty())
        for (Eigen::Index i = 0; i < loop.points.front().size(); ++i) sum += loop_area(loop.points, i);
    return sum;
}

}  // namespace sympl
