#pragma once
// Test particles of a Wisdom-Holman run: massless bodies moved by the star
// and the planets and moving neither, so that the planets' run is the same,
// bit for bit, with or without them. Each is split as a planet of mass -> 0
// would be (docs/planetary.md, "Test particles"): in democratic heliocentric
// coordinates (Duncan, Levison & Lee 1998, AJ 116, 2067, eq. 2-7) its
// heliocentric position and barycentric velocity, drifted about G m_0, kicked
// by the planets and carried by their jump; in Jacobi coordinates (Wisdom &
// Holman 1991, AJ 102, 1528, sec. 3) the outermost body of the hierarchy, its
// position from the centre of mass of star and planets, drifted about G m_0
// and kicked by every body less G m_0 Q / |Q|^3. The drifts run in lanes
// (kepler_lanes.hpp), the kicks in blocks of particles; the tangents of
// MEGNO per particle ride along (test_particle_megno.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "../../core/carried_state.hpp"
#include "../../core/dual.hpp"
#include "../../core/error.hpp"
#include "../coordinates.hpp"
#include "../interaction.hpp"
#include "../kepler/kepler_drift.hpp"
#include "../kepler/kepler_lanes.hpp"
#include "../kernels.hpp"
#include "../split_coordinates.hpp"
#include "test_particle_field.hpp"
#include "test_particle_megno.hpp"

namespace sympl {

// Test particles in an inertial frame (the frame of the planets' state):
// positions and velocities, and an id that stays with each particle.
template <class S>
struct test_particle_set {
    std::vector<S> x, y, z, vx, vy, vz;
    std::vector<std::uint64_t> id;

    std::size_t size() const { return x.size(); }
    void add(const std::array<S, 3>& r, const std::array<S, 3>& v) {
        id.push_back(id.empty() ? 0 : id.back() + 1);
        x.push_back(r[0]), y.push_back(r[1]), z.push_back(r[2]);
        vx.push_back(v[0]), vy.push_back(v[1]), vz.push_back(v[2]);
    }
    std::array<std::vector<S>*, 6> parts() { return {&x, &y, &z, &vx, &vy, &vz}; }
    std::array<const std::vector<S>*, 6> parts() const { return {&x, &y, &z, &vx, &vy, &vz}; }
};

namespace detail {
// Equal lengths and finite numbers, or an invalid_argument naming the particle.
template <class S>
void check_test_particles(const test_particle_set<S>& p, const std::string& who) {
    const char* names[] = {"x", "y", "z", "vx", "vy", "vz"};
    const auto parts = p.parts();
    for (int c = 0; c < 6; ++c)
        if (parts[std::size_t(c)]->size() != p.size() || p.id.size() != p.size())
            throw invalid_argument(who + ": " + std::to_string(parts[std::size_t(c)]->size()) + " values in " +
                                   names[c] + ", " + std::to_string(p.id.size()) + " ids and " +
                                   std::to_string(p.size()) + " in x; expected one per test particle in each");
    for (int c = 0; c < 6; ++c) {
        for (std::size_t i = 0; i < p.size(); ++i)
            if (!std::isfinite((*parts[std::size_t(c)])[i]))
                throw invalid_argument(who + ": " + names[c] + " of test particle " + std::to_string(p.id[i]) +
                                       " = " + number_text((*parts[std::size_t(c)])[i]) + "; expected a finite number");
    }
}

// What is left to read of a carried list: the bound of a count read next
// (a writer has no bound).
template <class List>
double carried_left(const List& l) {
    if constexpr (requires { l.left(); }) return l.left();
    else return std::numeric_limits<double>::infinity();
}

// Test particles' ids in a carried list: their count, which sizes nothing
// the list could not hold, then each (exact below 2^53).
template <class List, class Ids>
void carried_ids(List& l, Ids& id) {
    std::size_t n = id.size();
    const double left = carried_left(l);
    l.whole(n, "holds a bad number of test particles");
    l.check(double(n) < left, "holds a bad number of test particles");
    if constexpr (!std::is_const_v<Ids>) id.resize(n);
    for (auto& i : id) l.whole(i, "holds a bad particle id");
}

// Every particle (Q, v in q) drifted about gm over t one at a time, where
// the lanes refused the batch: a particle at the star or gone non-finite is
// made non-finite (for the caller to remove), the others drift.
template <class S>
void kepler_drift_one_by_one(std::array<std::vector<S>, 6>& q, S gm, S t) {
    for (std::size_t i = 0; i < q[0].size(); ++i) {
        S r[3] = {q[0][i], q[1][i], q[2][i]}, v[3] = {q[3][i], q[4][i], q[5][i]};
        try {
            kepler_drift_body(r, v, gm, t, std::ptrdiff_t(i));
        } catch (const invalid_argument&) {
            for (int c = 0; c < 3; ++c) r[c] = v[c] = std::numeric_limits<S>::quiet_NaN();
        }
        for (std::size_t c = 0; c < 3; ++c) q[c][i] = r[c], q[c + 3][i] = v[c];
    }
}
}  // namespace detail

// The flows of the Wisdom-Holman splitting on test particles, in the
// coordinates of Coordinates (split_coordinates.hpp), reading the planets'
// state (Q_i, v_i in those coordinates) at each kick.
template <class S, class Coordinates>
class test_particle_flows {
public:
    static constexpr bool jacobi = std::is_same_v<Coordinates, jacobi_coordinates<S>>;
    using field_type = test_particle_field<S, jacobi>;
    static constexpr std::size_t block = field_type::block;  // particles per block of a kick
    using dual_t = dual<S, 1>;

    test_particle_flows(const std::vector<double>& mass, double G)
        : mass_(mass), coords_(mass, G), field_(mass, G), gm0_(S(G) * S(mass[0])) {
        for (double m : mass_) total_mass_ += S(m);
        for (auto* v : {&pax_, &pay_, &paz_}) v->assign(mass_.size() - 1, S(0));
    }

    std::size_t size() const { return q_[0].size(); }

    // From particles in the inertial frame of the planets' inertial state x.
    template <class State>
    void load(const State& x, const test_particle_set<S>& in) {
        const auto [origin, velocity] = frame(x);
        const auto parts = in.parts();
        for (std::size_t c = 0; c < 6; ++c) {
            q_[c].resize(in.size());
            const S shift = c < 3 ? origin[c] : velocity[c - 3];
            for (std::size_t i = 0; i < in.size(); ++i) q_[c][i] = (*parts[c])[i] - shift;
        }
        id_ = in.id;
        if (tangent_.started()) tangent_.resize(size());
    }

    // Into `out` (ids kept), in the inertial frame of x.
    template <class State>
    void store(const State& x, test_particle_set<S>& out) const {
        const auto [origin, velocity] = frame(x);
        const auto parts = out.parts();
        for (std::size_t c = 0; c < 6; ++c) {
            parts[c]->resize(size());
            const S shift = c < 3 ? origin[c] : velocity[c - 3];
            for (std::size_t i = 0; i < size(); ++i) (*parts[c])[i] = q_[c][i] + shift;
        }
        out.id = id_;
    }

    // The flow of H_Kepler over t: every particle about G m_0, in lanes.
    void kepler(S t) {
        if (size() == 0) return;
        if (tangent_.on()) tangent_.kepler(q_, gm0_, t);
        const kepler_bodies<S> b{q_[0], q_[1], q_[2], q_[3], q_[4], q_[5]};
        try {
            fallbacks_ += kepler_drift_all<S>(b, gm0_, t);
        } catch (const invalid_argument&) {
            detail::kepler_drift_one_by_one(q_, gm0_, t);
        }
    }

    // The kick of t by the planets in state p (Q_i, v_i), after the planets'
    // own kick: in democratic heliocentric coordinates the planets' jump
    // first (the shift their kick gave them), then the interaction.
    template <class Planets>
    void kick(const Planets& p, S t) {
        if (size() == 0) return;
        if constexpr (!jacobi) jump(p, t);
        field_.place(p[0].data(), p[1].data(), p[2].data(), 0);
        if (tangent_.on()) tangent_kick(t, S(0));
        accelerate(q_[0].data(), q_[1].data(), q_[2].data(), 0, t);
    }

    // The lazy implementer's kernel (Wisdom, Holman & Touma 1996, eq. 10.6;
    // kernels.hpp) in place of kick(t), h the step: every body, planets and
    // particles, moved by lazy_kernel_displacement h^2 times its acceleration.
    template <class Planets>
    void lazy_kick(const Planets& p, S t, S h) {
        if (size() == 0) return;
        const std::size_t n = p[0].size();
        const S d = static_cast<S>(lazy_kernel_displacement) * h * h;
        coords_.accelerations(p[0].data(), p[1].data(), p[2].data(), pax_.data(), pay_.data(), paz_.data());
        for (std::size_t i = 0; i < n; ++i)
            pax_[i] = p[0][i] + d * pax_[i], pay_[i] = p[1][i] + d * pay_[i], paz_[i] = p[2][i] + d * paz_[i];
        field_.place(p[0].data(), p[1].data(), p[2].data(), 0);
        field_.place(pax_.data(), pay_.data(), paz_.data(), 1);
        if (tangent_.on()) tangent_kick(t, h);
        for (std::size_t c = 0; c < 3; ++c) moved_[c] = q_[c], lazy_a_[c].resize(size());
        for (std::size_t first = 0; first < size(); first += block)
            field_.at(q_[0].data(), q_[1].data(), q_[2].data(), lazy_a_[0].data() + first, lazy_a_[1].data() + first,
                      lazy_a_[2].data() + first, first, std::min(size(), first + block), 0);
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t i = 0; i < size(); ++i) moved_[c][i] += d * lazy_a_[c][i];
        accelerate(moved_[0].data(), moved_[1].data(), moved_[2].data(), 1, t);
    }

    // The state around the corrector (the tangent is paused there).
    std::array<std::vector<S>, 6> keep() const { return q_; }
    void restore(std::array<std::vector<S>, 6>&& kept) { q_ = std::move(kept); }

    // MEGNO per particle (test_particle_megno.hpp); paused around the corrector.
    test_particle_tangents<S>& tangents() { return tangent_; }
    const test_particle_tangents<S>& tangents() const { return tangent_; }
    void start_megno() { tangent_.start(size()); }

    std::uint64_t kepler_fallbacks() const { return fallbacks_; }

    // What the particles carry between steps (wisdom_holman_stepper::carried()):
    // Q, v and the id of each, and their MEGNO tangents.
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        for (auto& v : self.q_) l.numbers(v);
        detail::carried_ids(l, self.id_);
        for (const auto& v : self.q_) l.check(v.size() == self.id_.size(), "holds test particles of unequal lengths");
        l.part(self.tangent_);
        l.check(!self.tangent_.started() || self.tangent_.size() == self.id_.size(),
                "holds MEGNO tangents for another number of test particles");
    }

    // The particles' Q, v (by id()), and the star's and planets' positions
    // and velocities in the particles' frame (test_particle_field::bodies).
    const std::array<std::vector<S>, 6>& state() const { return q_; }
    const std::vector<std::uint64_t>& id() const { return id_; }
    template <class Planets>
    void bodies(const Planets& p, std::array<std::vector<S>, 6>& b) const {
        field_.bodies(p, b);
    }
    // Whether each kick keeps the particles' accelerations, for behind().
    void keep_accelerations(bool on) { keep_a_ = on; }

    // The planets' state p and the particles' as they were t before the last
    // kick ended, into planets and particles: a joined kick runs past a step's
    // end by the next step's first kick, t. A kick is linear in its time at
    // fixed positions: v - t a, and in democratic heliocentric coordinates
    // Q - t sum_j m_j v_j / m_0 (the jump keeps every difference of positions,
    // so a is the same before and after it, to rounding); exact to rounding.
    // Needs keep_accelerations on at that kick.
    template <class Planets>
    void behind(const Planets& p, S t, std::array<std::vector<S>, 6>& planets,
                std::array<std::vector<S>, 6>& particles) const {
        std::array<S, 3> shift{};
        if constexpr (!jacobi) {
            shift = planets_momentum(p);
            for (auto& s : shift) s *= t / S(mass_[0]);
        }
        for (std::size_t c = 0; c < 3; ++c) {
            planets[c].resize(p[c].size()), planets[c + 3].resize(p[c].size());
            for (std::size_t i = 0; i < p[c].size(); ++i)
                planets[c][i] = p[c][i] - shift[c], planets[c + 3][i] = p[c + 3][i] - t * p[c + 6][i];
            particles[c].resize(size()), particles[c + 3].resize(size());
            const S *x = q_[c].data(), *v = q_[c + 3].data(), *a = last_a_[c].data();
            S *y = particles[c].data(), *u = particles[c + 3].data();
            for (std::size_t i = 0; i < size(); ++i) y[i] = x[i] - shift[c], u[i] = v[i] - t * a[i];
        }
    }

    // Removes the particles with gone[i] set, keeping the others' order.
    void remove(const std::vector<char>& gone) {
        for (auto& v : q_) detail::remove_marked(v, gone);
        tangent_.remove(gone);
        detail::remove_marked(id_, gone);
    }

private:
    // The origin and velocity of the particles' frame in the inertial frame
    // of x: the star (democratic heliocentric) or the centre of mass
    // (Jacobi), and the centre of mass's velocity.
    template <class State>
    std::pair<std::array<S, 3>, std::array<S, 3>> frame(const State& x) const {
        std::array<S, 3> origin{}, velocity{};
        for (std::size_t j = 0; j < mass_.size(); ++j)
            for (std::size_t c = 0; c < 3; ++c) {
                const auto k = Eigen::Index(3 * j + c);
                if (jacobi) origin[c] += S(mass_[j]) * x.q[k];
                velocity[c] += x.p[k];
            }
        for (std::size_t c = 0; c < 3; ++c) {
            origin[c] = jacobi ? origin[c] / total_mass_ : x.q[Eigen::Index(c)];
            velocity[c] /= total_mass_;
        }
        return {origin, velocity};
    }

    // sum_j m_j v_j over the planets, summed as the planets' jump sums it:
    // the democratic heliocentric jump moves every Q by t / m_0 times it (DLL98 eq. 7).
    template <class Planets>
    std::array<S, 3> planets_momentum(const Planets& p) const {
        std::array<S, 3> sum{};
        for (std::size_t i = 0; i < p[0].size(); ++i)
            for (std::size_t c = 0; c < 3; ++c) sum[c] += S(mass_[i + 1]) * p[c + 3][i];
        return sum;
    }

    template <class Planets>
    void jump(const Planets& p, S t) {
        const auto [px, py, pz] = planets_momentum(p);
        const S s = t / S(mass_[0]);
        for (std::size_t i = 0; i < size(); ++i) q_[0][i] += s * px, q_[1][i] += s * py, q_[2][i] += s * pz;
    }

    // v += t a(x, y, z), block by block (x may be the lazy kernel's moved
    // positions); a kept in last_a_ while keep_accelerations is on.
    void accelerate(const S* x, const S* y, const S* z, int sources, S t) {
        S block_a[3][block];
        if (keep_a_)
            for (auto& v : last_a_) v.resize(size());
        const bool wide = std::is_floating_point_v<S> && wide_lanes();
        for (std::size_t first = 0; first < size(); first += block) {
            const std::size_t last = std::min(size(), first + block);
            S *ax = block_a[0], *ay = block_a[1], *az = block_a[2];
            if (keep_a_) ax = last_a_[0].data() + first, ay = last_a_[1].data() + first, az = last_a_[2].data() + first;
            if (wide) field_.at_wide(x, y, z, ax, ay, az, first, last, sources);
            else field_.at(x, y, z, ax, ay, az, first, last, sources);
            for (std::size_t l = 0; l < last - first; ++l)
                q_[3][first + l] += t * ax[l], q_[4][first + l] += t * ay[l], q_[5][first + l] += t * az[l];
        }
    }

    // The tangent over a kick of t (lazy_h != 0: the lazy kernel's, at the
    // moved positions): the field on dual numbers, at the sources before and
    // after the kernel's move.
    void tangent_kick(S t, S lazy_h) {
        tangent_.kick(q_, t, static_cast<S>(lazy_kernel_displacement) * lazy_h * lazy_h,
                      [this](const dual_t* x, dual_t* a, bool moved) {
                          field_.at(&x[0], &x[1], &x[2], &a[0], &a[1], &a[2], 0, 1, moved ? 1 : 0);
                      });
    }

    std::vector<double> mass_;
    Coordinates coords_;  // the planets' accelerations for the lazy kernel
    field_type field_;
    S gm0_, total_mass_ = 0;
    std::vector<S> pax_, pay_, paz_;
    std::array<std::vector<S>, 6> q_;  // Q, v per particle
    std::vector<std::uint64_t> id_;
    std::array<std::vector<S>, 3> moved_, lazy_a_;  // the lazy kernel's moved positions, their displacement
    std::array<std::vector<S>, 3> last_a_;          // the last kick's accelerations, if kept
    bool keep_a_ = false;
    test_particle_tangents<S> tangent_;
    std::uint64_t fallbacks_ = 0;
};

// The planets' flows and the particles' together, as the stepper and the
// corrector run them (kick, lazy_kick, drift, kepler): the planets first,
// the particles reading the planets' state after.
template <class Flows, class Particles, class S>
struct with_test_particles {
    Flows& planets;
    Particles& particles;

    void kick(S t) {
        planets.kick(t);
        particles.kick(planets.state(), t);
    }
    void lazy_kick(S t, S h) {
        planets.lazy_kick(t, h);
        particles.lazy_kick(planets.state(), t, h);
    }
    void drift(S t) {
        planets.drift(t);
        particles.kepler(t);
    }
    void kepler(S t) {
        planets.kepler(t);
        particles.kepler(t);
    }
};

}  // namespace sympl
