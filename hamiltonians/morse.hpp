#pragma once
// Morse oscillator (Morse 1929, Phys. Rev. 34, 57), per component:
//     H = p^2/(2m) + D (1 - exp(-a (q - r0)))^2,
// with its exact bound motion (E < D): y = exp(a (q - r0)) obeys
// y'' = (2 a^2 / m) (D - (D - E) y), a harmonic oscillation of angular frequency
// omega = a sqrt(2 (D - E) / m) about y_c = D / (D - E).
#include <cmath>
#include <string>

#include <sympl/core/error.hpp>
#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct morse {
    double mass = 1.0;
    double depth = 1.0;     // D
    double width = 1.0;     // a
    double position = 0.0;  // r0

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / (2 * mass); }
    template <class V> auto potential(const V& q) const {
        using std::exp;
        typename V::Scalar v(0);
        for (Eigen::Index i = 0; i < q.size(); ++i) {
            const auto s = 1 - exp(-width * (q[i] - position));
            v += depth * s * s;
        }
        return v;
    }
    template <class V> auto velocity(const V& p) const { return p * (1 / mass); }  // no division on the step's chain
    template <class V> void force(const V& q, V& f) const {
        using std::exp;
        f.resize(q.size());
        for (Eigen::Index i = 0; i < q.size(); ++i) {
            const auto e = exp(-width * (q[i] - position));
            f[i] = -2 * depth * width * (1 - e) * e;
        }
    }

    template <class S, int D>
    phase_space<S, D> exact(const phase_space<S, D>& x0, S t) const {
        using std::cos; using std::exp; using std::log; using std::sin; using std::sqrt;
        phase_space<S, D> x = x0;
        const S m(mass), Dp(depth), a(width);
        for (Eigen::Index i = 0; i < x0.size(); ++i) {
            const S e = exp(-a * (x0.q[i] - S(position)));
            const S E = x0.p[i] * x0.p[i] / (2 * m) + Dp * (1 - e) * (1 - e);
            if (!(E < Dp))
                throw invalid_argument("morse::exact: energy " + std::to_string(static_cast<double>(E)) +
                                       " is not below the well depth " + std::to_string(depth) + "; expected bound motion");
            const S y0 = 1 / e, dy0 = a * y0 * x0.p[i] / m, yc = Dp / (Dp - E), w = a * sqrt(2 * (Dp - E) / m);
            const S y = yc + (y0 - yc) * cos(w * t) + dy0 / w * sin(w * t);
            const S dy = -(y0 - yc) * w * sin(w * t) + dy0 * cos(w * t);
            x.q[i] = S(position) + log(y) / a;
            x.p[i] = m * dy / (a * y);
        }
        return x;
    }
};

}  // namespace sympl::hamiltonians
