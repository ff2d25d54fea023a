#pragma once
// Harmonic oscillator H = |p|^2/(2m) + m omega^2 |q|^2 / 2, any dimension.
// Sandvik's test system (Sandvik's lecture notes, "same oscillator as before"), with its exact flow.
#include <cmath>

#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct harmonic_oscillator {
    double mass = 1.0;
    double omega = 1.0;

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / (2 * mass); }
    template <class V> auto potential(const V& q) const { return q.squaredNorm() * (0.5 * mass * omega * omega); }
    template <class V> auto velocity(const V& p) const { return p * (1 / mass); }  // no division on the step's chain
    template <class V> void force(const V& q, V& f) const { f = q * (-mass * omega * omega); }

    // Exact state at time t from x0 at time 0.
    template <class S, int D>
    phase_space<S, D> exact(const phase_space<S, D>& x0, S t) const {
        using std::cos;
        using std::sin;
        const S c = cos(S(omega) * t), s = sin(S(omega) * t), mw = S(mass * omega);
        return phase_space<S, D>(x0.q * c + x0.p * (s / mw), x0.p * c - x0.q * (mw * s));
    }
};

}  // namespace sympl::hamiltonians
