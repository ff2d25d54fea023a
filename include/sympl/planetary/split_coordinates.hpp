#pragma once
// The two coordinate systems a Wisdom-Holman splitting runs in, as strategy
// types with one small interface, so that the stepper chooses once:
//     split(x), join(y)          inertial <-> these coordinates (coordinates.hpp)
//     momentum_mass(i)           P_i = momentum_mass(i) v_i of planet i (0-based)
//     kepler_gm(i), kepler(b, t) planet i's Kepler problem, all planets drifted
//     accelerations(x.., a..)    the interaction's accelerations (interaction.hpp)
//     jump(t, v.., x..)          the momenta's part of the kick (none in Jacobi)
// democratic_heliocentric_coordinates: Duncan, Levison & Lee 1998 (AJ 116,
// 2067, eq. 4-7): H_Kepler about G m_0, the interaction of the planets'
// pairs, the jump |sum_i P_i|^2 / 2m_0. jacobi_coordinates: Wisdom & Holman
// 1991 (AJ 102, 1528, sec. 3, eq. 10-11): planet i about GM_i = G m_0 eta_i /
// eta_{i-1} with mass m'_i, the rest a function of the positions alone.
#include <cstddef>
#include <span>
#include <tuple>
#include <type_traits>
#include <vector>

#include "../core/dual.hpp"
#include "coordinates.hpp"
#include "interaction.hpp"
#include "kepler/kepler_lanes.hpp"

namespace sympl {

template <class S>
class democratic_heliocentric_coordinates {
public:
    democratic_heliocentric_coordinates(std::vector<double> mass, double G)
        : mass_(std::move(mass)), G_(S(G)), gm_(S(G) * S(mass_[0])) {}

    template <class State>
    State split(const State& x) const { return to_democratic_heliocentric(x, std::span<const double>(mass_)); }
    template <class State>
    State join(const State& y) const { return from_democratic_heliocentric(y, std::span<const double>(mass_)); }

    S momentum_mass(std::size_t i) const { return S(mass_[i + 1]); }
    S kepler_gm(std::size_t) const { return gm_; }
    std::size_t kepler(const kepler_bodies<S>& b, S t) const { return kepler_drift_all<S>(b, gm_, t); }

    template <class T>
    void accelerations(const T* x, const T* y, const T* z, T* ax, T* ay, T* az) {
        pair_accelerations(mass_.size() - 1, x, y, z, mass_.data() + 1, G_, ax, ay, az);
    }

    // The flow of H_jump over t: every Q_i moves by t sum_j m_j v_j / m_0 (DLL98 eq. 7).
    template <class T>
    void jump(S t, const T* vx, const T* vy, const T* vz, T* x, T* y, T* z) const {
        const std::size_t n = mass_.size() - 1;
        T px(0), py(0), pz(0);
        for (std::size_t i = 0; i < n; ++i) {
            const S m(mass_[i + 1]);
            px += m * vx[i], py += m * vy[i], pz += m * vz[i];
        }
        const S s = t / S(mass_[0]);
        for (std::size_t i = 0; i < n; ++i) x[i] += s * px, y[i] += s * py, z[i] += s * pz;
    }

private:
    std::vector<double> mass_;
    S G_, gm_;
};

template <class S>
class jacobi_coordinates {
public:
    jacobi_coordinates(std::vector<double> mass, double G) : mass_(std::move(mass)), G_(S(G)) {
        const std::vector<double> eta = interior_masses(mass_), jm = jacobi_masses(mass_);
        for (std::size_t i = 1; i < mass_.size(); ++i) {
            eta_.push_back(S(eta[i - 1]));  // eta_{i-1}, the mass inside planet i
            jacobi_mass_.push_back(S(jm[i]));
            gm_.push_back(S(G) * S(mass_[0]) * (S(eta[i]) / S(eta[i - 1])));
        }
        std::get<0>(scratch_).resize(mass_.size());
        std::get<1>(scratch_).resize(mass_.size());
    }

    template <class State>
    State split(const State& x) const { return to_jacobi(x, std::span<const double>(mass_)); }
    template <class State>
    State join(const State& y) const { return from_jacobi(y, std::span<const double>(mass_)); }

    S momentum_mass(std::size_t i) const { return jacobi_mass_[i]; }
    S kepler_gm(std::size_t i) const { return gm_[i]; }
    std::size_t kepler(const kepler_bodies<S>& b, S t) const {
        return kepler_drift_all<S>(b, std::span<const S>(gm_), t);
    }

    template <class T>
    void accelerations(const T* x, const T* y, const T* z, T* ax, T* ay, T* az) {
        constexpr std::size_t which = std::is_same_v<T, S> ? 0 : 1;
        const jacobi_constants<S> c{std::span<const double>(mass_), eta_.data(), gm_.data(), G_};
        jacobi_accelerations(c, x, y, z, ax, ay, az, std::get<which>(scratch_));
    }

    // No jump: the interaction is a function of the positions alone.
    template <class T>
    void jump(S, const T*, const T*, const T*, T*, T*, T*) const {}

private:
    std::vector<double> mass_;
    S G_;
    std::vector<S> eta_, jacobi_mass_, gm_;
    std::tuple<bodies_scratch<S>, bodies_scratch<dual<S, 1>>> scratch_;
};

}  // namespace sympl
