#pragma once
// Scales of a Hamiltonian problem read off one state, for methods whose
// parameters carry units: the fastest angular frequency (the spectral radius
// of the Jacobian of f = (dH/dp, -dH/dq), by power iteration on J^2, whose
// eigenvalues are -omega^2 for oscillations), the momentum per position of
// each component (m omega for p^2/2m + V), and from them Tao's binding (Tao
// 2016: omega a few times the fastest frequency) in the state's units. Measurements: docs/nonseparable.md.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "../core/error.hpp"
#include "../core/general_hamiltonian.hpp"
#include "extended_phase_space.hpp"
#include "gauss/gauss_newton.hpp"

namespace sympl {

// The largest |eigenvalue| of J = df/dy at x: for H = p^2/2m + V it is the
// fastest angular frequency of the linearised motion; 0 for a free flow.
template <class H, class State>
double fastest_frequency(const H& h, const State& x) {
    using Real = double;
    const Eigen::Index n = x.q.size();
    detail::frozen_newton<Real, State::dimension> newton;
    newton.resize(n, 1);
    newton.jacobian_at(h, x.q, x.p);
    const auto& J = newton.scaled_jacobian();  // similar to J: the same eigenvalues
    Eigen::Matrix<Real, Eigen::Dynamic, 1> v = Eigen::Matrix<Real, Eigen::Dynamic, 1>::Ones(2 * n), w;
    for (Eigen::Index k = 0; k < 2 * n; ++k) v[k] += Real(k) / Real(4 * n);  // not orthogonal to any mode
    Real lambda2 = 0;
    for (int it = 0; it < 60; ++it) {
        w = J * (J * v);
        const Real norm = w.norm(), before = v.norm();
        if (!(norm > 0) || !std::isfinite(norm)) return norm > 0 ? norm : 0.0;
        lambda2 = norm / before;
        v = w / norm;
    }
    return std::sqrt(lambda2);
}

// max |p| / max |q| of the state, 1 where either half is zero.
template <class State>
double momentum_scale(const State& x) {
    double q = 0, p = 0;
    for (Eigen::Index k = 0; k < x.q.size(); ++k) {
        q = std::max(q, double(std::fabs(double(primal(x.q[k])))));
        p = std::max(p, double(std::fabs(double(primal(x.p[k])))));
    }
    return q > 0 && p > 0 ? p / q : 1.0;
}

// Per component k, sqrt(|d2H/dq_k^2| / |d2H/dp_k^2|) at x: m omega_k for
// H = p^2/2m + V, so that bodies of masses 1e-8 and 1 are each bound in their
// own units; momentum_scale(x) where either derivative vanishes.
template <class H, class State>
std::vector<double> momentum_scales(const H& h, const State& x) {
    const Eigen::Index n = x.q.size();
    detail::frozen_newton<double, State::dimension> newton;
    newton.resize(n, 1);
    newton.jacobian_at(h, x.q, x.p);
    const auto& J = newton.scaled_jacobian();  // D^-1 J D: J(r, c) = J_s(r, c) d_r / d_c
    const auto& d = newton.scales();
    std::vector<double> kappa(std::size_t(n), momentum_scale(x));
    for (Eigen::Index k = 0; k < n; ++k) {
        const double h_pp = std::fabs(J(k, n + k) * d[k] / d[n + k]), h_qq = std::fabs(J(n + k, k) * d[n + k] / d[k]);
        if (h_pp > 0 && h_qq > 0 && std::isfinite(h_pp) && std::isfinite(h_qq)) kappa[std::size_t(k)] = std::sqrt(h_qq / h_pp);
    }
    return kappa;
}

// Tao's options for H from the state x: omega = factor times the fastest
// frequency there (Tao 2016 asks a few times it), the binding in the state's
// units. A state with no frequency (a free flow) keeps omega = 20.
template <class H, class State>
tao_options tao_options_for(const H& h, const State& x, double factor = 4) {
    if (!std::isfinite(factor) || !(factor > 0))
        throw invalid_argument("tao_options_for: factor = " + detail::number_text(factor) +
                               "; expected a finite multiple > 0 of the fastest frequency");
    tao_options o;
    const double w = fastest_frequency(h, x);
    if (w > 0 && std::isfinite(w)) o.omega = factor * w;
    o.momentum_scale = momentum_scale(x);
    o.momentum_scales = momentum_scales(h, x);
    return o;
}

}  // namespace sympl
