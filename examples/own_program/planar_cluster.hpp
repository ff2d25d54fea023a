#pragma once
// A second system of one's own: equal point masses in a plane bound by
// gravity, H = sum |p_i|^2 / (2m) - sum_{i<j} G m^2 / |q_i - q_j|, body i at
// (q[2i], q[2i+1]). The same H as examples/formulas/cluster.toml writes as
// formulas, so that the two ways of bringing one's own system can be set
// side by side (docs/formulas.md, "Against the same system in C++").
#include <Eigen/Core>

namespace my {

struct planar_cluster {
    double G = 1.0, m = 1.0;

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / (2 * m); }
    // Templated on the scalar, so that dual numbers differentiate it (Gauss,
    // force-gradient kicks, MEGNO).
    template <class V> auto potential(const V& q) const {
        using std::sqrt;
        typename V::Scalar v(0);
        const Eigen::Index n = q.size() / 2;
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index j = i + 1; j < n; ++j) {
                const auto dx = q[2 * i] - q[2 * j], dy = q[2 * i + 1] - q[2 * j + 1];
                v -= G * m * m / sqrt(dx * dx + dy * dy);
            }
        return v;
    }
    template <class V> auto velocity(const V& p) const { return (p / m).eval(); }
    // -dV/dq, each pair once: the pair's pull added to one body, taken from the other.
    template <class V> void force(const V& q, V& f) const {
        using std::sqrt;
        f.resize(q.size());
        f.setZero();
        const Eigen::Index n = q.size() / 2;
        for (Eigen::Index i = 0; i < n; ++i)
            for (Eigen::Index j = i + 1; j < n; ++j) {
                const auto dx = q[2 * i] - q[2 * j], dy = q[2 * i + 1] - q[2 * j + 1];
                const auto r2 = dx * dx + dy * dy;
                const auto pull = G * m * m / (r2 * sqrt(r2));
                f[2 * i] -= pull * dx;
                f[2 * i + 1] -= pull * dy;
                f[2 * j] += pull * dx;
                f[2 * j + 1] += pull * dy;
            }
    }
};

}  // namespace my
