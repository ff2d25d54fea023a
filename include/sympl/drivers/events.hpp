#pragma once
// Events located on the dense output (dense_output.hpp): a function
// g(state, t) of the orbit (q[1] for a Poincare section, q.p for pericentre
// and apocentre passages, |q| - r for a close approach), its sign changes
// found between step ends (and, optionally, at interior points of the step,
// so that g crossing zero and back within one step is not missed), and each
// root located by Brent's method (Brent 1973, "Algorithms for Minimization
// without Derivatives", ch. 4) in the step's fraction th, on the step's
// interpolant: the Hermite interpolant of event_options::order, or over a
// controlled run the stepper's own interpolation where it has one.
//
// An event time is a zero of g along the interpolant to within
// event_options::time_tolerance + 4 eps dt; the interpolant's own error
// moves it by that error over |dg/dt|. A crossing counts in the step (ta, tb]
// in which g goes from < 0 to >= 0 (rising) or from > 0 to <= 0 (falling): a
// zero at t0 is not an event, one exactly at a step end is counted once.
//
// The steps are those integrate_until (or integrate_controlled) makes with an
// observer at every step, not shortened to land on an event (a splitting
// stepper's kicks are then not joined across steps, which changes its
// rounding against an unobserved run). An event whose action is `stop` ends
// the run at the first such crossing: x is then the state INTERPOLATED at the
// event time, the stepper has taken the step containing the event and no
// further one, and the events recorded are those up to and including it.
// section_crossings (analysis/poincare_section.hpp) is the event g = q[k],
// rising, run through detail::run_events with integrate_steps' steps.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "fixed_step.hpp"
#include "../core/phase_space.hpp"
#include "controlled.hpp"
#include "dense_output.hpp"
#include "stepper_interpolant.hpp"

namespace sympl {

enum class event_direction { rising, falling, both };
enum class event_action { record, stop };

template <class State>
struct event {
    std::function<typename State::scalar(const State&, typename State::scalar)> g;
    event_direction direction = event_direction::both;
    event_action action = event_action::record;
};

struct event_options {
    hermite_order order = hermite_order::cubic;
    // Points inside each step, equally spaced, where g is also evaluated on the
    // interpolant (each costs nothing but g; any > 0 needs the derivatives at
    // every step end: one force and one velocity per step, quintic two velocities).
    int interior_points = 0;
    // Absolute tolerance on an event time (>= 0); 0 means to rounding.
    double time_tolerance = 0;
};

template <class State>
struct event_hit {
    std::size_t event = 0;  // index into the events given
    typename State::scalar t{};
    State state;             // interpolated at t
    bool rising = false;     // g went from < 0 to >= 0
};

// Summary: dense_summary over fixed steps, controlled_dense_summary over a controlled run.
template <class State, class Summary = dense_summary>
struct event_run : Summary {
    std::vector<event_hit<State>> hits;  // in time order
    bool stopped = false;                // a stop event ended the run (then t is its time)
};

namespace detail {
// A zero of f on [a, b] with fa < 0 <= fb or fa > 0 >= fb: Brent's method
// (Brent 1973, ch. 4). The result b has a sign change of f between b and the
// kept point c with |c - b| <= 2 tol, tol = 2 eps |b| + tolerance / 2.
template <class T, class F>
T brent_root(F&& f, T a, T b, T fa, T fb, T tolerance) {
    using std::abs;
    const T eps = std::numeric_limits<T>::epsilon();
    T c = a, fc = fa, d = b - a, e = d;
    for (int iteration = 0; iteration < 200; ++iteration) {
        if (abs(fc) < abs(fb)) {  // b is the best estimate; c stays across the root from it
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        const T tol = 2 * eps * abs(b) + tolerance / 2;
        const T m = (c - b) / 2;
        if (abs(m) <= tol || fb == T(0)) return b;
        if (abs(e) < tol || abs(fa) <= abs(fb)) {
            d = e = m;  // bisection
        } else {
            T p, q;
            const T s = fb / fa;
            if (a == c) {  // secant
                p = 2 * m * s;
                q = 1 - s;
            } else {  // inverse quadratic through a, b, c
                const T qa = fa / fc, r = fb / fc;
                p = s * (2 * m * qa * (qa - r) - (b - a) * (r - 1));
                q = (qa - 1) * (r - 1) * (s - 1);
            }
            if (p > 0) q = -q; else p = -p;
            const T previous = e;
            e = d;
            if (2 * p < 3 * m * q - abs(tol * q) && p < abs(previous * q / 2)) {
                d = p / q;
            } else {
                d = e = m;
            }
        }
        a = b;
        fa = fb;
        b += abs(d) > tol ? d : (m > 0 ? tol : -tol);
        fb = f(b);
        if ((fb > 0) == (fc > 0)) {  // keep the sign change between b and c
            c = a;
            fc = fa;
            d = e = b - a;
        }
    }
    return b;
}

template <class T>
void check_event_value(T g, std::size_t i, T t, const char* who) {
    using std::isfinite;
    if (!isfinite(g))
        throw invalid_argument(std::string(who) + ": event " + std::to_string(i) + "'s g = " + number(g) +
                               " at t = " + number(t) + "; expected a finite value");
}
}  // namespace detail

namespace detail {
template <class State>
void check_events(const std::vector<event<State>>& events, const event_options& options, const char* who) {
    if (options.interior_points < 0 || options.interior_points > 1000)
        throw invalid_argument(std::string(who) + ": interior_points = " + std::to_string(options.interior_points) +
                               "; expected 0 <= interior_points <= 1000");
    if (!(options.time_tolerance >= 0) || !std::isfinite(options.time_tolerance))
        throw invalid_argument(std::string(who) + ": time_tolerance = " + number(options.time_tolerance) +
                               "; expected a finite tolerance >= 0");
    for (std::size_t i = 0; i < events.size(); ++i) {
        const auto d = events[i].direction;
        const auto a = events[i].action;
        if (!events[i].g)
            throw invalid_argument(std::string(who) + ": event " + std::to_string(i) +
                                   " has no function g; expected g(state, t)");
        if (d != event_direction::rising && d != event_direction::falling && d != event_direction::both)
            throw invalid_argument(std::string(who) + ": event " + std::to_string(i) + "'s direction = " +
                                   std::to_string(static_cast<int>(d)) + "; expected rising, falling or both");
        if (a != event_action::record && a != event_action::stop)
            throw invalid_argument(std::string(who) + ": event " + std::to_string(i) + "'s action = " +
                                   std::to_string(static_cast<int>(a)) + "; expected record or stop");
    }
}

// The crossings of the events inside one step, g sampled at `fractions` of
// it (g_samples: one row of fractions.size() values per event), each located
// by Brent's method in the fraction th on the interpolant; added to found.
template <class State, class Interpolant, class G, class TimeAt>
void crossings_in_step(Interpolant& dense, const std::vector<event<State>>& events,
                       const std::vector<typename State::scalar>& g_samples,
                       const std::vector<typename State::scalar>& fractions, typename State::scalar tolerance, G& g_of,
                       TimeAt& time_at, State& y, std::vector<event_hit<State>>& found) {
    using T = typename State::scalar;
    const std::size_t m = fractions.size();
    for (std::size_t i = 0; i < events.size(); ++i)
        for (std::size_t j = 0; j + 1 < m; ++j) {
            const T ga = g_samples[i * m + j], gb = g_samples[i * m + j + 1];
            const bool rising = ga < 0 && gb >= 0, falling = ga > 0 && gb <= 0;
            const auto d = events[i].direction;
            if (!((rising && d != event_direction::falling) || (falling && d != event_direction::rising))) continue;
            const auto along = [&](T th) {
                dense.evaluate_fraction(th, y);
                return g_of(i, y, time_at(th));
            };
            event_hit<State> hit;
            hit.event = i;
            hit.rising = rising;
            const T th = brent_root(along, fractions[j], fractions[j + 1], ga, gb, tolerance);
            hit.t = time_at(th);
            dense.evaluate_fraction(th, hit.state);
            found.push_back(std::move(hit));
        }
}

// The events of a run that drive(observer) makes, observing every step, and
// returns the summary of; stopped(steps) gives that summary when a stop
// event ends the run after `steps` steps. dense interpolates each step
// (step_interpolant or stepper_interpolant).
template <class Summary, class Interpolant, class State, class Drive, class Stopped>
event_run<State, Summary> locate_events(Interpolant& dense, State& x, const std::vector<event<State>>& events,
                                        const event_options& options, const char* who, Drive&& drive,
                                        Stopped&& stopped) {
    using T = typename State::scalar;
    check_events(events, options, who);
    struct stop_signal {};  // ends the driver from the observer at a stop event
    const std::size_t n_events = events.size();
    const int k = options.interior_points;
    std::vector<T> g_end(n_events), g_samples(n_events * std::size_t(k + 2)), fractions(std::size_t(k + 2));
    std::vector<event_hit<State>> found;
    event_run<State, Summary> result;
    State y = x;
    std::size_t observed = 0;
    const auto g_of = [&](std::size_t i, const State& s, T t) {
        const T g = events[i].g(s, t);
        detail::check_event_value(g, i, t, who);
        return g;
    };

    auto observer = [&](const State& s, T t) {
        if (observed++ == 0) {
            dense.start(s, t);
            for (std::size_t i = 0; i < n_events; ++i) g_end[i] = g_of(i, s, t);
            return;
        }
        dense.push(s, t);
        const T ta = dense.t0(), tb = dense.t1(), step = tb - ta;
        // g at the samples: the start (kept from the last step), interior points, the end,
        // at fractions th of the step (times ta + th step).
        const std::size_t m = std::size_t(k) + 2;
        const auto time_at = [&](T th) { return th == T(1) ? tb : ta + step * th; };
        fractions[0] = 0;
        fractions[m - 1] = 1;
        for (std::size_t j = 1; j + 1 < m; ++j) fractions[j] = T(j) / T(m - 1);
        for (std::size_t i = 0; i < n_events; ++i) {
            g_samples[i * m] = g_end[i];
            g_samples[i * m + m - 1] = g_end[i] = g_of(i, s, tb);
        }
        for (std::size_t j = 1; j + 1 < m; ++j) {
            dense.evaluate_fraction(fractions[j], y);
            for (std::size_t i = 0; i < n_events; ++i) g_samples[i * m + j] = g_of(i, y, time_at(fractions[j]));
        }
        found.clear();
        // The root is sought in th: its rounding is relative to the step, not to t.
        crossings_in_step(dense, events, g_samples, fractions, T(options.time_tolerance) / step, g_of, time_at, y, found);
        std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
        for (auto& hit : found) {
            const bool stop = events[hit.event].action == event_action::stop;
            result.hits.push_back(std::move(hit));
            if (stop) throw stop_signal{};
        }
    };

    try {
        const auto run = drive(observer);
        static_cast<std::decay_t<decltype(run)>&>(result) = run;
    } catch (const stop_signal&) {
        const event_hit<State>& last = result.hits.back();
        x = last.state;
        result.stopped = true;
        const auto run = stopped(observed - 1);
        static_cast<std::decay_t<decltype(run)>&>(result) = run;
        result.t = static_cast<double>(primal(last.t));
    }
    result.extra_force_evaluations = dense.force_evaluations();
    result.extra_velocity_evaluations = dense.velocity_evaluations();
    return result;
}

// Over fixed steps with the Hermite interpolant: drive is integrate_until or integrate_steps.
template <class Stepper, class H, class Drive>
event_run<typename Stepper::state_type> run_events(Stepper& stepper, const H& h, typename Stepper::state_type& x,
                                                   const std::vector<event<typename Stepper::state_type>>& events,
                                                   const event_options& options, const char* who, Drive&& drive) {
    step_interpolant<H, typename Stepper::state_type> dense(h, options.order);
    const auto f0 = detail::forces(stepper);
    const auto v0 = detail::velocities(stepper);
    return locate_events<dense_summary>(dense, x, events, options, who, drive, [&](std::size_t steps) {
        run_summary r;
        r.steps = steps;
        r.force_evaluations = detail::forces(stepper) - f0;
        r.velocity_evaluations = detail::velocities(stepper) - v0;
        return r;
    });
}

}  // namespace detail

// Runs stepper from x at t0 up to t_end with steps of dt (integrate_until's
// steps) and reports the events' crossings; x ends at t_end, or at the first
// stop event, interpolated there. h is the Hamiltonian the stepper runs.
template <fixed_step_stepper Stepper, class H>
    requires separable_hamiltonian<H, typename Stepper::state_type::vector>
event_run<typename Stepper::state_type> integrate_events(Stepper& stepper, const H& h,
                                                         typename Stepper::state_type& x, typename Stepper::scalar t0,
                                                         typename Stepper::scalar t_end, typename Stepper::scalar dt,
                                                         const std::vector<event<typename Stepper::state_type>>& events,
                                                         event_options options = {}) {
    using detail::number;
    const char* who = "integrate_events";
    detail::check_dt(dt, who);
    check_time_span(who, t0, t_end);
    return detail::run_events(stepper, h, x, events, options, who,
                              [&](auto& observer) { return integrate_until(stepper, x, t0, t_end, dt, observer); });
}

// The same with the stepper's own Hamiltonian.
template <fixed_step_stepper Stepper>
    requires requires(const Stepper& s) { s.hamiltonian(); }
event_run<typename Stepper::state_type> integrate_events(Stepper& stepper, typename Stepper::state_type& x,
                                                         typename Stepper::scalar t0, typename Stepper::scalar t_end,
                                                         typename Stepper::scalar dt,
                                                         const std::vector<event<typename Stepper::state_type>>& events,
                                                         event_options options = {}) {
    return integrate_events(stepper, stepper.hamiltonian(), x, t0, t_end, dt, events, options);
}

// Over a controlled run (drivers/controlled.hpp): integrate_controlled's
// steps, and the events located on the stepper's own interpolation where it
// has one (interpolating_stepper: the RKN pairs), otherwise on the Hermite
// interpolant of options.order. A stop event ends the run as above.
template <class Stepper, class H>
    requires error_estimating_stepper<Stepper> && separable_hamiltonian<H, typename Stepper::state_type::vector>
event_run<typename Stepper::state_type, controlled_dense_summary> integrate_events(
    Stepper& stepper, const H& h, typename Stepper::state_type& x, typename Stepper::scalar t0,
    typename Stepper::scalar t_end, const control_options& control,
    const std::vector<event<typename Stepper::state_type>>& events, event_options options = {}) {
    using State = typename Stepper::state_type;
    const char* who = "integrate_events";
    check_time_span(who, t0, t_end);
    control_summary progress;  // kept step by step, for a stop event
    const auto drive = [&](auto& observer) {
        detail::control_loop(stepper, x, t0, t_end, control, observer, progress);
        return progress;
    };
    const auto stopped = [&](std::size_t) { return progress; };
    if constexpr (interpolating_stepper<Stepper>) {
        stepper_interpolant<Stepper> dense(stepper);
        return detail::locate_events<controlled_dense_summary>(dense, x, events, options, who, drive, stopped);
    } else {
        step_interpolant<H, State> dense(h, options.order);
        return detail::locate_events<controlled_dense_summary>(dense, x, events, options, who, drive, stopped);
    }
}

// The same with the stepper's own Hamiltonian.
template <class Stepper>
    requires error_estimating_stepper<Stepper> && requires(const Stepper& s) { s.hamiltonian(); }
event_run<typename Stepper::state_type, controlled_dense_summary> integrate_events(
    Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0, typename Stepper::scalar t_end,
    const control_options& control, const std::vector<event<typename Stepper::state_type>>& events,
    event_options options = {}) {
    return integrate_events(stepper, stepper.hamiltonian(), x, t0, t_end, control, events, options);
}

}  // namespace sympl
