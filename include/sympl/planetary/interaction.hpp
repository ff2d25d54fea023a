#pragma once
// The planets' interaction accelerations, the kick of the Wisdom-Holman
// splittings, for any scalar (double, or a dual number for the tangent map):
// the pairwise Newtonian accelerations, and in Jacobi coordinates the
// accelerations of the perturbation H - H_Kepler (Wisdom & Holman 1991, AJ
// 102, 1528, sec. 3), derived in docs/planetary.md ("Jacobi coordinates").
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace sympl {

// a_i = sum_{j != i} G m_j (r_j - r_i) / |r_j - r_i|^3 over n bodies of
// masses m[0..n).
template <class S, class T>
void pair_accelerations(std::size_t n, const T* x, const T* y, const T* z, const double* m, S G, T* ax, T* ay,
                        T* az) {
    using std::sqrt;
    for (std::size_t i = 0; i < n; ++i) ax[i] = ay[i] = az[i] = T(0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            const T dx = x[j] - x[i], dy = y[j] - y[i], dz = z[j] - z[i];
            const T r2 = dx * dx + dy * dy + dz * dz;
            const T k = G / (r2 * sqrt(r2));
            const T ki = k * S(m[j]), kj = k * S(m[i]);
            ax[i] += ki * dx, ay[i] += ki * dy, az[i] += ki * dz;
            ax[j] -= kj * dx, ay[j] -= kj * dy, az[j] -= kj * dz;
        }
}

// All bodies' positions (less X_N) and accelerations, for the Jacobi kick.
template <class T>
struct bodies_scratch {
    std::vector<T> x, y, z, ax, ay, az;
    void resize(std::size_t n) {
        for (auto* v : {&x, &y, &z, &ax, &ay, &az}) v->assign(n, T(0));
    }
};

// What the Jacobi interaction needs of the masses: eta_{i-1} (the mass
// inside planet i) and GM_i = G m_0 eta_i / eta_{i-1} per planet.
template <class S>
struct jacobi_constants {
    std::span<const double> mass;  // star first
    const S* eta;
    const S* gm;
    S G;
};

// All bodies' positions x_j - X_N (star first, n + 1 of them) from the
// planets' Jacobi positions (x, y, z), from the outside in:
// X_{j-1} = X_j - (m_j / eta_j) Q_j, x_j = Q_j + X_{j-1}.
template <class S, class T>
void jacobi_centred_positions(const jacobi_constants<S>& c, const T* x, const T* y, const T* z, T* bx, T* by,
                              T* bz) {
    const std::size_t n = c.mass.size() - 1;
    T X(0), Y(0), Z(0);  // X_{j-1} - X_N, from the outside in
    for (std::size_t j = n; j-- > 0;) {
        const S w = S(c.mass[j + 1]) / (c.eta[j] + S(c.mass[j + 1]));
        X -= w * x[j], Y -= w * y[j], Z -= w * z[j];
        bx[j + 1] = x[j] + X, by[j + 1] = y[j] + Y, bz[j + 1] = z[j] + Z;
    }
    bx[0] = X, by[0] = Y, bz[0] = Z;
}

// The accelerations a'_i of the Jacobi interaction at Jacobi positions (x,
// y, z) of the planets (WH91 sec. 3; docs/planetary.md):
//     a'_i = a_i - sum_{j < i} m_j a_j / eta_{i-1} + G M_i Q_i / |Q_i|^3,
// a_j the inertial accelerations of all pairs, the star's included.
template <class S, class T>
void jacobi_accelerations(const jacobi_constants<S>& c, const T* x, const T* y, const T* z, T* ax, T* ay, T* az,
                          bodies_scratch<T>& b) {
    using std::sqrt;
    const std::size_t n = c.mass.size() - 1;
    jacobi_centred_positions(c, x, y, z, b.x.data(), b.y.data(), b.z.data());
    pair_accelerations(n + 1, b.x.data(), b.y.data(), b.z.data(), c.mass.data(), c.G, b.ax.data(), b.ay.data(),
                       b.az.data());
    T sx = S(c.mass[0]) * b.ax[0], sy = S(c.mass[0]) * b.ay[0], sz = S(c.mass[0]) * b.az[0];
    for (std::size_t i = 0; i < n; ++i) {
        const T r2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
        const T k = c.gm[i] / (r2 * sqrt(r2));
        const S inner = 1 / c.eta[i];
        ax[i] = b.ax[i + 1] - sx * inner + k * x[i];
        ay[i] = b.ay[i + 1] - sy * inner + k * y[i];
        az[i] = b.az[i + 1] - sz * inner + k * z[i];
        const S m(c.mass[i + 1]);
        sx += m * b.ax[i + 1], sy += m * b.ay[i + 1], sz += m * b.az[i + 1];
    }
}

}  // namespace sympl
