#pragma once
// Close encounters and losses of test particles (test_particles.hpp),
// checked after every step of a Wisdom-Holman run: each particle-planet
// closest approach inside the step located on the cubic Hermite of their
// separation (Hairer, Norsett & Wanner, Solving ODE I, eq. II.6.7) by Brent's
// method, logged in Hill radii (Hill 1878); collisions (with the star also at
// a pericentre passed inside the step: Murray & Dermott 1999, ch. 2), escapes,
// unbound and non-finite particles removed and logged, never lost silently.
// The checks, their order and the screens' bounds: docs/planetary.md.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include "../../core/error.hpp"
#include "../../core/wide_lanes.hpp"
#include "../../drivers/events.hpp"
#include "test_particles.hpp"

namespace sympl {

struct encounter_options {
    // Collision radius per body, star first (empty: no collisions); a
    // particle closer than radius[k] to body k is removed.
    std::vector<double> radius;
    // A particle farther than this from the star is removed (escape).
    double escape_distance = std::numeric_limits<double>::infinity();
    // A particle farther than this from the star and unbound is removed.
    double unbound_distance = std::numeric_limits<double>::infinity();
    // Closest approaches within this many Hill radii of a planet are logged (0: none).
    double log_within_hill = 0;
};

// A closest approach of a particle to planet `body` (1..N) at `time`.
template <class S>
struct encounter_record {
    S time;
    std::uint64_t particle;
    std::size_t body;
    S distance, hill_radii;
};

enum class loss_reason { collision, escape, unbound, non_finite };

inline std::string loss_reason_name(loss_reason r) {
    switch (r) {
        case loss_reason::collision: return "collision";
        case loss_reason::escape: return "escape";
        case loss_reason::unbound: return "unbound";
        case loss_reason::non_finite: return "non_finite";
    }
    return "unknown";
}

// A particle removed at `time` (the end of the step it was found in):
// `body` and `distance` the body hit and the distance (collision), or the
// star's distance (escape, unbound); `energy` its v^2/2 - G M / r.
template <class S>
struct loss_record {
    S time;
    std::uint64_t particle;
    loss_reason reason;
    std::size_t body;
    S distance, energy;
};

namespace detail {
// The separation d and its rate u of a pair at a step's two ends, and the
// cubic Hermite through them in the step's fraction th (dt the step).
template <class S>
struct pair_step {
    std::array<S, 3> d0, u0, d1, u1;
    S dt;
    std::array<S, 3> at(S th, std::array<S, 3>* rate = nullptr) const {
        const S h00 = (1 + 2 * th) * (1 - th) * (1 - th), h10 = th * (1 - th) * (1 - th);
        const S h01 = th * th * (3 - 2 * th), h11 = th * th * (th - 1);
        const S g00 = 6 * th * (th - 1), g10 = (1 - th) * (1 - 3 * th), g01 = -g00, g11 = th * (3 * th - 2);
        std::array<S, 3> p;
        for (int c = 0; c < 3; ++c) {
            p[c] = h00 * d0[c] + h10 * dt * u0[c] + h01 * d1[c] + h11 * dt * u1[c];
            if (rate) (*rate)[c] = (g00 * d0[c] + g10 * dt * u0[c] + g01 * d1[c] + g11 * dt * u1[c]) / dt;
        }
        return p;
    }
    // d.d' on the interpolant (its zero from < 0 to > 0 is the closest approach).
    S closing(S th) const {
        std::array<S, 3> u;
        const std::array<S, 3> p = at(th, &u);
        return p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
    }
};

template <class S>
S norm3(const std::array<S, 3>& a) {
    return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}
}  // namespace detail

// The checks after each step, fed the particles' and the bodies' positions
// and velocities in one frame (test_particle_flows::frame_state) at each step's end.
template <class S>
class encounter_tracker {
public:
    using arrays = std::array<std::vector<S>, 6>;

    encounter_tracker() = default;
    encounter_tracker(encounter_options options, std::vector<double> mass, double G)
        : options_(std::move(options)), mass_(std::move(mass)), G_(S(G)) {
        const std::string who = "encounter_options: ";
        if (!options_.radius.empty() && options_.radius.size() != mass_.size())
            throw invalid_argument(who + std::to_string(options_.radius.size()) + " radii for " +
                                   std::to_string(mass_.size()) + " bodies; expected one per body (star first) or none");
        for (std::size_t k = 0; k < options_.radius.size(); ++k)
            if (!(options_.radius[k] >= 0) || !std::isfinite(options_.radius[k]))
                throw invalid_argument(who + "radius of body " + std::to_string(k) + " = " +
                                       detail::number_text(options_.radius[k]) + "; expected a finite radius >= 0");
        for (const auto& [name, v] : {std::pair<const char*, double>{"escape_distance", options_.escape_distance},
                                      {"unbound_distance", options_.unbound_distance},
                                      {"log_within_hill", options_.log_within_hill}})
            if (!(v >= 0))
                throw invalid_argument(who + name + " = " + detail::number_text(v) + "; expected a value >= 0");
        for (double m : mass_) total_gm_ += G_ * S(m);
        using std::cbrt;
        for (std::size_t k = 0; k < mass_.size(); ++k) hill_factor_.push_back(cbrt(S(mass_[k]) / (3 * S(mass_[0]))));
        hill_.resize(mass_.size());
        on_ = true;
    }

    bool on() const { return on_; }
    void set_time(S t) { time_ = t; }
    S time() const { return time_; }
    const std::vector<encounter_record<S>>& encounters() const { return encounters_; }
    const std::vector<loss_record<S>>& losses() const { return losses_; }
    void clear_logs() { encounters_.clear(), losses_.clear(); }

    // The tracker's part of a carried list (test_particle_run): whether it is
    // on, then its time and both logs, so that a resumed run's logs are the
    // whole run's. Its options are the caller's: track_encounters again before restoring.
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        bool on = self.on_;
        l.flag(on);
        l.check(on == self.on_, self.on_ ? "holds no encounter log, but the stepper tracks encounters"
                                         : "holds an encounter log, but the stepper tracks none (track_encounters "
                                           "before restoring)");
        if (!on) return;
        l.number(self.time_);
        log_count(l, self.encounters_, 5, "holds a bad number of encounters");
        for (auto& e : self.encounters_) {
            l.number(e.time);
            l.whole(e.particle, "holds a bad particle id");
            body_index(self, l, e.body, "holds an encounter with no such body");
            l.number(e.distance), l.number(e.hill_radii);
        }
        log_count(l, self.losses_, 6, "holds a bad number of losses");
        for (auto& loss : self.losses_) {
            l.number(loss.time);
            l.whole(loss.particle, "holds a bad particle id");
            std::uint64_t reason = std::uint64_t(loss.reason);
            l.whole(reason, "holds no such loss reason");
            l.check(reason < 4, "holds no such loss reason");
            if constexpr (!std::is_const_v<Self>) loss.reason = loss_reason(reason);
            body_index(self, l, loss.body, "holds a loss to no such body");
            l.number(loss.distance), l.number(loss.energy);
        }
    }

    // The state the next step starts from.
    void begin(const arrays& particles, const arrays& bodies) {
        previous_ = particles;
        previous_bodies_ = bodies;
    }

    // After a step of dt ending at particles and bodies (star first); gone[i]
    // set for each particle removed (logged). The ends become the next step's
    // start: copied, or swapped with p (after_step_taking: p leaves with the old start).
    void after_step(const arrays& p, const arrays& b, const std::vector<std::uint64_t>& id, S dt,
                    std::vector<char>& gone) {
        const std::size_t losses_before = losses_.size();
        check(p, b, id, dt, gone);
        previous_ = p;
        keep_ends(b, gone, losses_before);
    }
    void after_step_taking(arrays& p, const arrays& b, const std::vector<std::uint64_t>& id, S dt,
                           std::vector<char>& gone) {
        const std::size_t losses_before = losses_.size();
        check(p, b, id, dt, gone);
        std::swap(previous_, p);
        keep_ends(b, gone, losses_before);
    }

private:
    static constexpr std::size_t block = 256;  // particles whose pairs are marked at a time

    // A log's length, each record `per` numbers: read back, no longer than the list could hold.
    template <class List, class Log>
    static void log_count(List& l, Log& log, double per, const char* what) {
        std::size_t n = log.size();
        const double limit = detail::carried_left(l) / per + 1;
        l.whole(n, what);
        l.check(double(n) < limit, what);
        if constexpr (!std::is_const_v<Log>) log.resize(n);
    }
    template <class Self, class List, class Body>
    static void body_index(Self& self, List& l, Body& k, const char* what) {
        l.whole(k, what);
        l.check(k < self.mass_.size(), what);
    }

    void check(const arrays& p, const arrays& b, const std::vector<std::uint64_t>& id, S dt, std::vector<char>& gone) {
        time_ += dt;
        const std::size_t n = p[0].size(), bodies = b[0].size();
        gone.assign(n, 0);
        for (std::size_t k = 1; k < bodies; ++k) hill_[k] = hill_radius(b, k);  // once per step, not per pair
        const bool wide = std::is_floating_point_v<S> && wide_lanes();
        for (std::size_t i = 0; i < n; ++i) {
            if (i % block == 0) {
                if (wide) mark_wide(p, b, i, std::min(n, i + block), dt);
                else mark_pairs(p, b, i, std::min(n, i + block), dt), mark_quiet(p, b, i, std::min(n, i + block), dt);
            }
            if (quiet_[i % block] != 0) continue;
            const std::array<S, 3> r{p[0][i] - b[0][0], p[1][i] - b[1][0], p[2][i] - b[2][0]};
            const S star = detail::norm3(r);
            S v2 = 0;
            for (int c = 3; c < 6; ++c) v2 += p[std::size_t(c)][i] * p[std::size_t(c)][i];
            const S energy = v2 / 2 - total_gm_ / star;
            bool finite = std::isfinite(energy);
            for (std::size_t c = 0; c < 6; ++c) finite = finite && std::isfinite(p[c][i]);
            if (!finite) {
                lose(gone, i, id[i], loss_reason::non_finite, 0, star, energy);
                continue;
            }
            if (!options_.radius.empty() && star < S(options_.radius[0])) {
                lose(gone, i, id[i], loss_reason::collision, 0, star, energy);
                continue;
            }
            if (const S q = pericentre_passed(p, b, i, dt); q < S(options_.radius.empty() ? 0 : options_.radius[0])) {
                lose(gone, i, id[i], loss_reason::collision, 0, q, energy);
                continue;
            }
            for (std::size_t k = 1; k < bodies && !gone[i]; ++k)
                if (look_[(k - 1) * block + i % block] != 0) approach(p, b, i, k, id[i], dt, energy, gone);
            if (gone[i]) continue;
            if (star > S(options_.escape_distance)) lose(gone, i, id[i], loss_reason::escape, 0, star, energy);
            else if (star > S(options_.unbound_distance) && energy > 0)
                lose(gone, i, id[i], loss_reason::unbound, 0, star, energy);
        }
    }

    // previous_ holds this step's particles; the bodies and the removals too.
    void keep_ends(const arrays& b, const std::vector<char>& gone, std::size_t losses_before) {
        previous_bodies_ = b;
        if (losses_.size() != losses_before)  // most steps lose none: no pass over the arrays
            for (std::size_t c = 0; c < 6; ++c) detail::remove_marked(previous_[c], gone);
    }

    // look_[(k - 1) * block + i - first] for particles [first, last): whether
    // the pair with body k needs approach(): a minimum of d.d' inside the
    // step near enough to reach, or the end inside the radius (the bound in
    // squares, with a margin of rounding: docs/planetary.md). One loop per
    // body, no branch, no square root, in SIMD lanes.
    void mark_pairs(const arrays& p, const arrays& b, std::size_t first, std::size_t last, S dt) {
        const std::size_t bodies = b[0].size();
        if (bodies < 2) return;
        look_.resize((bodies - 1) * block);
        constexpr S eps = std::numeric_limits<S>::epsilon();
        for (std::size_t k = 1; k < bodies; ++k) {
            const S radius = options_.radius.empty() ? S(0) : S(options_.radius[k]);
            const S reach2 = radius * radius * (1 + 8 * eps);
            const S reach = std::max(radius, S(options_.log_within_hill) * hill_[k]);
            const S near = 2 * reach * reach * (1 + 64 * eps), pace = 8 * dt * dt * (1 + 64 * eps);
            const S q0[6] = {previous_bodies_[0][k], previous_bodies_[1][k], previous_bodies_[2][k],
                             previous_bodies_[3][k], previous_bodies_[4][k], previous_bodies_[5][k]};
            const S q1[6] = {b[0][k], b[1][k], b[2][k], b[3][k], b[4][k], b[5][k]};
            const S *x0 = previous_[0].data(), *x1 = previous_[1].data(), *x2 = previous_[2].data(),
                    *u0 = previous_[3].data(), *u1 = previous_[4].data(), *u2 = previous_[5].data();
            const S *y0 = p[0].data(), *y1 = p[1].data(), *y2 = p[2].data(), *v0 = p[3].data(), *v1 = p[4].data(),
                    *v2 = p[5].data();
            S* look = look_.data() + (k - 1) * block;
            // Marks are doubles chosen by a select (GCC 12 with SSE2 vectorises no
            // bool-to-integer); SYMPL_ARRAYS_APART: they alias no coordinate.
            SYMPL_ARRAYS_APART
            for (std::size_t i = first; i < last; ++i) {
                const S a0 = x0[i] - q0[0], a1 = x1[i] - q0[1], a2 = x2[i] - q0[2];
                const S w0 = u0[i] - q0[3], w1 = u1[i] - q0[4], w2 = u2[i] - q0[5];
                const S e0 = y0[i] - q1[0], e1 = y1[i] - q1[1], e2 = y2[i] - q1[2];
                const S z0 = v0[i] - q1[3], z1 = v1[i] - q1[4], z2 = v2[i] - q1[5];
                const S g0 = a0 * w0 + a1 * w1 + a2 * w2, g1 = e0 * z0 + e1 * z1 + e2 * z2;
                const S start2 = a0 * a0 + a1 * a1 + a2 * a2, end2 = e0 * e0 + e1 * e1 + e2 * e2;
                const S speed0 = w0 * w0 + w1 * w1 + w2 * w2, speed1 = z0 * z0 + z1 * z1 + z2 * z2;
                const S closest2 = start2 < end2 ? start2 : end2, speed2 = speed0 > speed1 ? speed0 : speed1;
                look[i - first] =
                    (((g0 < 0) & (g1 > 0) & (closest2 < near + pace * speed2)) | (end2 <= reach2)) ? S(1) : S(0);
            }
        }
    }

    // Both markings, compiled for AVX2 (wide_lanes.hpp).
    SYMPL_AVX2_CLONE void mark_wide(const arrays& p, const arrays& b, std::size_t first, std::size_t last, S dt) {
        mark_pairs(p, b, first, last, dt);
        mark_quiet<true>(p, b, first, last, dt);
    }

    // quiet_[i - first] = 1 for the particles [first, last) no check below can
    // remove or log (each test with a margin of rounding: a vector sqrt or a
    // contracted product may differ by an ulp); the few others take every
    // check, scalar. Wide: in the AVX2 clone.
    template <bool Wide = false>
    void mark_quiet(const arrays& p, const arrays& b, std::size_t first, std::size_t last, S dt) {
        quiet_.resize(block);
        const S margin = 16 * std::numeric_limits<S>::epsilon();
        const S inner = (options_.radius.empty() ? S(0) : S(options_.radius[0])) * (1 + margin);
        const S escape = S(options_.escape_distance) * (1 - margin), unbound = S(options_.unbound_distance) * (1 - margin);
        const S c0 = b[0][0], c1 = b[1][0], c2 = b[2][0], largest = std::numeric_limits<S>::max();
        const S *x0 = p[0].data(), *x1 = p[1].data(), *x2 = p[2].data(), *u0 = p[3].data(), *u1 = p[4].data(),
                *u2 = p[5].data();
        // The orbit about the star (pericentre_passed): its velocity, mu = G m_0.
        const S cv0 = b[3][0], cv1 = b[4][0], cv2 = b[5][0];
        const S mu = G_ * S(mass_[0]), reach = 2 * mu * inner * (1 + margin), to_bind = 2 * mu / total_gm_;
        const S stretch = inner / (2 * mu);
        const S turn = 4 * std::numbers::pi_v<S> * std::numbers::pi_v<S> * mu * mu * (1 - margin), dt2 = dt * dt;
        const bool checked = inner > 0;
        S* quiet = quiet_.data();
        const std::size_t m = last - first;
        star_.resize(block);
        SYMPL_ARRAYS_APART
        for (std::size_t i = first; i < last; ++i) {
            const S d0 = x0[i] - c0, d1 = x1[i] - c1, d2 = x2[i] - c2;
            star_[i - first] = d0 * d0 + d1 * d1 + d2 * d2;
        }
        detail::square_roots<Wide>(star_.data(), star_.data(), m);
        SYMPL_ARRAYS_APART
        for (std::size_t i = first; i < last; ++i) {
            const S star = star_[i - first];
            const S kinetic = (u0[i] * u0[i] + u1[i] * u1[i] + u2[i] * u2[i]) / 2, potential = total_gm_ / star;
            // About the star (pericentre_passed; bounds in docs/planetary.md):
            // the end receding or the period at most 2 |dt|, and h^2 (lowered
            // by its rounding, h^2 = d^2 w^2 - (d.w)^2) small enough for q < R;
            // bind = -2E, raised or lowered by its rounding where that flags more.
            const S d0 = x0[i] - c0, d1 = x1[i] - c1, d2 = x2[i] - c2;
            const S w0 = u0[i] - cv0, w1 = u1[i] - cv1, w2 = u2[i] - cv2;
            const S dw = d0 * w0 + d1 * w1 + d2 * w2, w2_ = w0 * w0 + w1 * w1 + w2 * w2;
            const S h2 = star * star * w2_ * (1 - 16 * margin) - dw * dw;
            const S pull = potential * to_bind, bind = pull - w2_, slack = margin * (pull + w2_);
            const S lifted = 1 + stretch * (bind - slack), high = bind + slack;
            const bool low = (h2 < reach) | (h2 * lifted < reach);  // h^2 min(1, lifted): GCC 12 keeps two tests in lanes
            const bool turns = (dw * dt > 0) | (4 * high * high * high * dt2 >= turn);
            const bool plunge = low & turns & checked;
            // The energy finite, and bound with room to spare; NaN fails every test.
            quiet[i - first] = (star > inner) & (star <= escape) & (kinetic <= largest) & (potential <= largest) &
                                       ((star <= unbound) | (kinetic < potential * (1 - margin))) & !plunge
                                   ? S(1)
                                   : S(0);
        }
        for (std::size_t k = 1; k < b[0].size(); ++k) {
            const S* look = look_.data() + (k - 1) * block;
            for (std::size_t i = 0; i < m; ++i) quiet[i] = look[i] != 0 ? S(0) : quiet[i];
        }
    }

    // Particle i and body k over the step: the closest approach located
    // where d.d' changes sign from < 0 to > 0, logged, and a collision.
    void approach(const arrays& p, const arrays& b, std::size_t i, std::size_t k, std::uint64_t id, S dt, S energy,
                  std::vector<char>& gone) {
        detail::pair_step<S> s;
        s.dt = dt;
        for (std::size_t c = 0; c < 3; ++c) {
            s.d0[c] = previous_[c][i] - previous_bodies_[c][k], s.u0[c] = previous_[c + 3][i] - previous_bodies_[c + 3][k];
            s.d1[c] = p[c][i] - b[c][k], s.u1[c] = p[c + 3][i] - b[c + 3][k];
        }
        const S radius = options_.radius.empty() ? S(0) : S(options_.radius[k]);
        const S g0 = s.d0[0] * s.u0[0] + s.d0[1] * s.u0[1] + s.d0[2] * s.u0[2];  // d.d' at the ends (mark_pairs)
        const S g1 = s.d1[0] * s.u1[0] + s.d1[1] * s.u1[1] + s.d1[2] * s.u1[2];
        const bool minimum_inside = g0 < 0 && g1 > 0;
        const S end = detail::norm3(s.d1);
        const S hill = hill_[k];
        const S reach = std::max(radius, S(options_.log_within_hill) * hill);
        S closest = end;
        const S speed = std::max(detail::norm3(s.u0), detail::norm3(s.u1));
        if (minimum_inside && std::min(detail::norm3(s.d0), end) - speed * dt * 2 < reach) {
            const S th = detail::brent_root([&](S t) { return s.closing(t); }, S(0), S(1), g0, g1,
                                            S(4) * std::numeric_limits<S>::epsilon());
            closest = detail::norm3(s.at(th));
            if (options_.log_within_hill > 0 && closest < S(options_.log_within_hill) * hill)
                encounters_.push_back({time_ - dt + th * dt, id, k, closest, closest / hill});
        }
        if (radius > 0 && std::min(closest, end) < radius)
            lose(gone, i, id, loss_reason::collision, k, std::min(closest, end), energy);
    }

    // q = h^2 / (mu (1 + e)) of particle i's orbit about the star (mu = G m_0)
    // at the step's end if a pericentre was, or may have been, passed within
    // the step (d.u from < 0 to > 0, or period <= 2 |dt|); infinity otherwise.
    S pericentre_passed(const arrays& p, const arrays& b, std::size_t i, S dt) const {
        std::array<S, 3> d0, u0, d1, u1;
        for (std::size_t c = 0; c < 3; ++c) {
            d0[c] = previous_[c][i] - previous_bodies_[c][0], u0[c] = previous_[c + 3][i] - previous_bodies_[c + 3][0];
            d1[c] = p[c][i] - b[c][0], u1[c] = p[c + 3][i] - b[c + 3][0];
        }
        const S mu = G_ * S(mass_[0]);
        const S g0 = (d0[0] * u0[0] + d0[1] * u0[1] + d0[2] * u0[2]) * dt;
        const S g1 = (d1[0] * u1[0] + d1[1] * u1[1] + d1[2] * u1[2]) * dt;
        const std::array<S, 3> h{d1[1] * u1[2] - d1[2] * u1[1], d1[2] * u1[0] - d1[0] * u1[2],
                                 d1[0] * u1[1] - d1[1] * u1[0]};
        const S h2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2], r = detail::norm3(d1);
        const S bind = 2 * mu / r - (u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
        using std::sqrt;
        const bool circles = bind > 0 && std::numbers::pi_v<S> * mu <= bind * sqrt(bind) * (dt < 0 ? -dt : dt);
        if (!((g0 < 0 && g1 > 0) || circles)) return std::numeric_limits<S>::infinity();
        // e from the eccentricity vector w x h / mu - d / |d|, which keeps its
        // digits on a near-circular orbit (sqrt(1 - bind h^2 / mu^2) loses half).
        const std::array<S, 3> e{(u1[1] * h[2] - u1[2] * h[1]) / mu - d1[0] / r,
                                 (u1[2] * h[0] - u1[0] * h[2]) / mu - d1[1] / r,
                                 (u1[0] * h[1] - u1[1] * h[0]) / mu - d1[2] / r};
        return h2 / (mu * (1 + detail::norm3(e)));
    }

    // a (m_k / 3 m_0)^(1/3), a body k's distance from the star at the step's end.
    S hill_radius(const arrays& b, std::size_t k) const {
        const std::array<S, 3> r{b[0][k] - b[0][0], b[1][k] - b[1][0], b[2][k] - b[2][0]};
        return detail::norm3(r) * hill_factor_[k];
    }

    void lose(std::vector<char>& gone, std::size_t i, std::uint64_t id, loss_reason why, std::size_t body, S distance,
              S energy) {
        gone[i] = 1;
        losses_.push_back({time_, id, why, body, distance, energy});
    }


    encounter_options options_;
    std::vector<double> mass_;
    S G_ = 0, total_gm_ = 0, time_ = 0;
    std::vector<S> hill_factor_, hill_;  // (m_k / 3 m_0)^(1/3), and the Hill radii at this step's end
    std::vector<S> look_;               // mark_pairs' marks for the current block (1: look)
    std::vector<S> quiet_;              // mark_quiet's marks for the current block (1: no check can act)
    std::vector<S> star_;               // and its distances from the star
    arrays previous_, previous_bodies_;
    std::vector<encounter_record<S>> encounters_;
    std::vector<loss_record<S>> losses_;
    bool on_ = false;
};

}  // namespace sympl
