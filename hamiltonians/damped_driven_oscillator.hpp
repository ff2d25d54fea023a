#pragma once
// Damped, driven oscillator m x'' = -k x - b v + F0 cos(Omega t), componentwise
// in any dimension. Newton's form (q = x, p = v), with the force split as
// F(x, t) = -k x + F0 cos(Omega t) and drag G(v) = b v for the classic
// steppers and the damped leapfrog (Sandvik's lecture notes), and as the
// conformal system dv/dt = F(x, t)/m - (b/m) v for the splitting tables
// (methods/conformal_splitting.hpp). The exact solution covers every regime: under-, over-
// and critically damped, undamped, and undamped at resonance.
#include <cmath>

#include <sympl/core/phase_space.hpp>
#include <sympl/methods/conformal_splitting.hpp>

namespace sympl::hamiltonians {

struct damped_driven_oscillator {
    double mass = 1.0;
    double stiffness = 1.0;        // k
    double damping = 0.0;          // b
    double drive_amplitude = 0.0;  // F0
    double drive_frequency = 0.0;  // Omega

    static constexpr bool p_is_velocity = true;
    static constexpr bool velocity_dependent = true;

    template <class V, class T> void dq_dt(const V&, const V& v, T, V& out) const { out = v; }
    template <class V, class T> void dp_dt(const V& x, const V& v, T t, V& out) const {
        using std::cos;
        out = (x * T(-stiffness) - v * T(damping)) / T(mass);
        out.array() += T(drive_amplitude) * cos(T(drive_frequency) * t) / T(mass);
    }
    // F(x, t) and G(v), m a = F - G (Sandvik's lecture notes).
    template <class V, class T> void force(const V& x, T t, V& out) const {
        using std::cos;
        out = x * T(-stiffness);
        out.array() += T(drive_amplitude) * cos(T(drive_frequency) * t);
    }
    template <class V> void drag(const V& v, V& out) const { out = v * typename V::Scalar(damping); }

    // The conformal form (conformal_splitting.hpp): p = v, so the force on p
    // is F(x, t)/m and the damping rate of dv/dt = ... - gamma v is b/m.
    double damping_rate() const { return damping / mass; }
    template <class V, class T> void driven_force(const V& x, T t, V& out) const {
        force(x, t, out);
        out /= T(mass);
    }
    template <class V> void velocity(const V& v, V& out) const { out = v; }
    // The drive is harmonic: the stepper adds F0 cos(Omega t)/m itself, a
    // cosine and a sine per step instead of a cosine per kick.
    harmonic_drive harmonic_drive_term() const { return {drive_amplitude / mass, drive_frequency, 0}; }
    template <class V> void undriven_force(const V& x, V& out) const { out = x * typename V::Scalar(-stiffness / mass); }

    // Mechanical energy m v^2/2 + k x^2/2 (not conserved unless b = F0 = 0).
    template <class S, int D> S energy(const phase_space<S, D>& x) const {
        return S(mass) * x.p.squaredNorm() / 2 + S(stiffness) * x.q.squaredNorm() / 2;
    }

    // Exact state at time t from x0 at time 0.
    template <class S, int D>
    phase_space<S, D> exact(const phase_space<S, D>& x0, S t) const {
        phase_space<S, D> x = x0;
        for (Eigen::Index i = 0; i < x0.size(); ++i) exact_component(x0.q[i], x0.p[i], t, x.q[i], x.p[i]);
        return x;
    }

private:
    // x(t) = x_h(t) + x_p(t): x_p the steady response to the drive, x_h the free
    // motion e^{-gamma t} (X C(t) + (V + gamma X) S(t)) that fits the initial data.
    template <class S>
    void exact_component(S x0, S v0, S t, S& x, S& v) const {
        using std::cos; using std::sin; using std::cosh; using std::sinh; using std::exp; using std::sqrt; using std::abs;
        const S m(mass), k(stiffness), b(damping), F0(drive_amplitude), W(drive_frequency);
        S xp = 0, vp = 0, xp0 = 0, vp0 = 0;
        if (F0 != S(0)) {
            const S re = k - m * W * W, im = b * W, d2 = re * re + im * im;
            if (d2 == S(0)) {  // undamped resonance: x_p = F0 t sin(W t) / (2 m W)
                const S c = F0 / (2 * m * W);
                xp = c * t * sin(W * t);
                vp = c * (sin(W * t) + W * t * cos(W * t));
            } else {           // x_p = Re(A e^{i W t}), A = F0 / (k - m W^2 + i b W)
                const S ar = F0 * re / d2, ai = -F0 * im / d2;
                xp = ar * cos(W * t) - ai * sin(W * t);
                vp = -W * (ar * sin(W * t) + ai * cos(W * t));
                xp0 = ar;
                vp0 = -W * ai;
            }
        }
        const S X = x0 - xp0, V = v0 - vp0;
        const S gamma = b / (2 * m), w0sq = k / m, disc = w0sq - gamma * gamma;
        S C, dC, Sf, dS;  // C(t), C'(t), S(t), S'(t)
        if (abs(disc) <= S(1e-14) * (w0sq + gamma * gamma)) {  // critical (or free)
            C = 1; dC = 0; Sf = t; dS = 1;
        } else if (disc > 0) {  // underdamped
            const S w = sqrt(disc);
            C = cos(w * t); dC = -w * sin(w * t); Sf = sin(w * t) / w; dS = cos(w * t);
        } else {  // overdamped
            const S s = sqrt(-disc);
            C = cosh(s * t); dC = s * sinh(s * t); Sf = sinh(s * t) / s; dS = cosh(s * t);
        }
        const S decay = exp(-gamma * t), xh = decay * (X * C + (V + gamma * X) * Sf);
        x = xh + xp;
        v = decay * (X * dC + (V + gamma * X) * dS) - gamma * xh + vp;
    }
};

}  // namespace sympl::hamiltonians
