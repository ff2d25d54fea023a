#pragma once
// The gravitational field that test particles of a Wisdom-Holman run feel
// besides their Kepler term (test_particles.hpp): in democratic heliocentric
// coordinates the planets' pull, sum_k G m_k (s_k - Q) / |s_k - Q|^3 with s_k
// the planets' heliocentric positions (Duncan, Levison & Lee 1998, AJ 116,
// 2067, eq. 2-7, for a body of mass -> 0); in Jacobi coordinates every body's
// pull from its position about the centre of mass of star and planets, less
// the Kepler term's G m_0 Q / |Q|^3 (Wisdom & Holman 1991, AJ 102, 1528,
// sec. 3). Evaluated source by source over blocks of particles, so that the
// loops over particles vectorise; on dual numbers too, for MEGNO's tangents.
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

#include "../../core/wide_lanes.hpp"
#include "../coordinates.hpp"
#include "../interaction.hpp"

namespace sympl {

template <class S, bool Jacobi>
class test_particle_field {
public:
    static constexpr std::size_t block = 64;  // particles per block

    test_particle_field(const std::vector<double>& mass, double G)
        : mass_(mass), G_(S(G)), gm0_(S(G) * S(mass[0])) {
        const std::vector<double> eta = interior_masses(mass_);
        for (std::size_t i = 1; i < mass_.size(); ++i) {
            eta_.push_back(S(eta[i - 1]));
            gm_.push_back(S(G) * S(mass_[0]) * (S(eta[i]) / S(eta[i - 1])));
        }
        // The bodies a particle feels besides its Kepler term: the planets
        // (democratic heliocentric), or every body (Jacobi).
        for (std::size_t k = Jacobi ? 0 : 1; k < mass_.size(); ++k) source_gm_.push_back(S(G) * S(mass_[k]));
        for (auto& set : sources_)
            for (auto& v : set) v.assign(source_gm_.size(), S(0));
    }

    // The sources of set 0 (the planets' positions (x, y, z), in their
    // coordinates) or set 1 (the lazy kernel's moved positions), placed in
    // the particles' frame.
    void place(const S* x, const S* y, const S* z, int set) {
        auto& s = sources_[std::size_t(set)];
        if constexpr (Jacobi) {
            jacobi_centred_positions(constants(), x, y, z, s[0].data(), s[1].data(), s[2].data());
        } else {
            for (std::size_t k = 0; k < s[0].size(); ++k) s[0][k] = x[k], s[1][k] = y[k], s[2][k] = z[k];
        }
    }

    // The accelerations of particles first..last (at most `block`) at
    // (x, y, z) into (ax, ay, az), from index 0, by the sources of `set`.
    // Wide: in the AVX2 clone (at_wide). Each source's position and GM are
    // held in locals: read through the vectors inside the loop they would
    // be reloaded after every store, and the loop would not vectorise.
    template <class T, bool Wide = false>
    void at(const T* x, const T* y, const T* z, T* ax, T* ay, T* az, std::size_t first, std::size_t last,
            int set) const {
        const auto& [sx, sy, sz] = sources_[std::size_t(set)];
        const std::size_t m = last - first, sources = source_gm_.size();
        x += first, y += first, z += first;
        T r2[block], r[block];
        for (std::size_t l = 0; l < m; ++l) ax[l] = ay[l] = az[l] = T(0);
        for (std::size_t k = 0; k < sources; ++k) {
            const S px = sx[k], py = sy[k], pz = sz[k], gm = source_gm_[k];
            SYMPL_ARRAYS_APART
            for (std::size_t l = 0; l < m; ++l) {
                const T dx = px - x[l], dy = py - y[l], dz = pz - z[l];
                r2[l] = dx * dx + dy * dy + dz * dz;
            }
            detail::square_roots<Wide>(r2, r, m);
            SYMPL_ARRAYS_APART
            for (std::size_t l = 0; l < m; ++l) {
                const T f = gm / (r2[l] * r[l]);
                ax[l] += f * (px - x[l]), ay[l] += f * (py - y[l]), az[l] += f * (pz - z[l]);
            }
        }
        if constexpr (Jacobi) {
            SYMPL_ARRAYS_APART
            for (std::size_t l = 0; l < m; ++l) r2[l] = x[l] * x[l] + y[l] * y[l] + z[l] * z[l];
            detail::square_roots<Wide>(r2, r, m);
            const S gm0 = gm0_;
            SYMPL_ARRAYS_APART
            for (std::size_t l = 0; l < m; ++l) {
                const T f = gm0 / (r2[l] * r[l]);
                ax[l] += f * x[l], ay[l] += f * y[l], az[l] += f * z[l];
            }
        }
    }

    // The same, compiled for AVX2 (wide_lanes.hpp).
    template <class T>
    SYMPL_AVX2_CLONE void at_wide(const T* x, const T* y, const T* z, T* ax, T* ay, T* az, std::size_t first,
                                  std::size_t last, int set) const {
        at<T, true>(x, y, z, ax, ay, az, first, last, set);
    }

    // The star's and planets' positions and velocities in the particles'
    // frame from the planets' state p (Q_i, v_i), so that differences with a
    // particle's are separations and their rates: democratic heliocentric, the
    // star at 0 moving at -sum_j m_j v_j / m_0 (the jump's velocity, which
    // every Q shares), the planets at Q_j with v_j; Jacobi, every body's
    // x_j - X_N and its rate (jacobi_centred_positions).
    template <class Planets>
    void bodies(const Planets& p, std::array<std::vector<S>, 6>& b) const {
        const std::size_t n = p[0].size();
        for (auto& v : b) v.assign(n + 1, S(0));
        if constexpr (Jacobi) {
            jacobi_centred_positions(constants(), p[0].data(), p[1].data(), p[2].data(), b[0].data(), b[1].data(),
                                     b[2].data());
            jacobi_centred_positions(constants(), p[3].data(), p[4].data(), p[5].data(), b[3].data(), b[4].data(),
                                     b[5].data());
        } else {
            for (std::size_t c = 0; c < 6; ++c)
                for (std::size_t i = 0; i < n; ++i) b[c][i + 1] = p[c][i];
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t c = 3; c < 6; ++c) b[c][0] -= S(mass_[i + 1]) * p[c][i] / S(mass_[0]);
        }
    }

private:
    jacobi_constants<S> constants() const {
        return jacobi_constants<S>{std::span<const double>(mass_), eta_.data(), gm_.data(), G_};
    }

    std::vector<double> mass_;
    S G_, gm0_;
    std::vector<S> eta_, gm_, source_gm_;
    std::array<std::array<std::vector<S>, 3>, 2> sources_;  // the planets' positions, the lazy kernel's moved ones
};

}  // namespace sympl
