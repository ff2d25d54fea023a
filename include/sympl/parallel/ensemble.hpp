#pragma once
// One stepper set-up (Hamiltonian, table, dt, span, what to measure) run over
// many initial states: W trajectories at a time in one SIMD state
// (batch.hpp), the batches spread over threads (OpenMP).
//
// Results come back in input order. Each trajectory's arithmetic is fixed by
// its own start and the options alone (the batches are the index blocks
// [kW, (k+1)W) whatever the thread count, and lanes never mix), so the
// results are bitwise identical for any number of threads or processes
// (ensemble_mpi.hpp). A trajectory that blows up is reported with its step and
// time, and the others run on.
//
// Threads: OpenMP, which GCC and Clang ship with the compiler (libgomp,
// libomp): a consumer needs no new package, and built without -fopenmp the
// same code runs on one thread.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "batch.hpp"
#include "../analysis/chaos_indicator.hpp"
#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/phase_space.hpp"
#include "../core/splitting_stepper.hpp"
#include "../core/table.hpp"

namespace sympl {

struct ensemble_options {
    double t0 = 0;
    double dt = 0;                 // > 0
    std::size_t steps = 0;         // >= 1
    std::size_t sample_every = 1;  // energy error, MEGNO and the reduction every k steps and at the end
    bool energy = true;            // measure the max relative energy error
    // A relative energy error above this ends a trajectory as blown up (the
    // program uses 1e3: a run that escapes is reported where it escaped).
    double divergence = std::numeric_limits<double>::infinity();
    bool megno = false;            // carry a tangent vector and measure MEGNO (chaos_indicator.hpp)
    int threads = 0;               // 0: OpenMP's default (OMP_NUM_THREADS, else every core)
};

template <class State>
struct trajectory_result {
    State final_state;              // at the end, or the last finite state before a blow-up
    bool stable = true;
    std::size_t blowup_step = 0;    // unstable: the step (1-based) that broke the run
    double blowup_time = 0;         // and the time it started from
    std::string failure;            // unstable: what happened
    double max_energy_error = -1;   // -1: not measured
    double megno = std::nan("");    // <Y> at the last sample before the end or the blow-up
    double quantity = std::nan(""); // the reduction's value
};

// A per-trajectory quantity: a copy of the reduction is called as
// r(state, t) at t0 and at every sample (with plain double states, also in
// batches), and r.value() is stored in trajectory_result::quantity.
struct no_reduction {
    template <class State>
    void operator()(const State&, double) {}
    double value() const { return std::nan(""); }
};

namespace detail {

template <int L>
using lane_scalar = std::conditional_t<L == 1, double, batch<double, L>>;

// The plain (no tangent) part of a component.
template <class S>
const S& value_part(const S& x) { return x; }
template <class S, int N>
const S& value_part(const dual<S, N>& x) { return x.value; }
template <class S>
S& value_part(S& x) { return x; }
template <class S, int N>
S& value_part(dual<S, N>& x) { return x.value; }

inline void check_ensemble_options(const ensemble_options& o) {
    if (!std::isfinite(o.dt) || !(o.dt > 0))
        throw invalid_argument("run_ensemble: dt = " + number_text(o.dt) + "; expected a finite step size > 0");
    if (!std::isfinite(o.t0))
        throw invalid_argument("run_ensemble: t0 = " + number_text(o.t0) + "; expected a finite time");
    if (o.steps == 0 || o.sample_every == 0)
        throw invalid_argument("run_ensemble: steps = " + std::to_string(o.steps) + ", sample_every = " +
                               std::to_string(o.sample_every) + "; expected both >= 1");
    if (!(o.divergence > 0))
        throw invalid_argument("run_ensemble: divergence = " + number_text(o.divergence) + "; expected a number > 0");
    if (o.threads < 0)
        throw invalid_argument("run_ensemble: threads = " + std::to_string(o.threads) +
                               "; expected 0 (OpenMP's default) or a count >= 1");
}

template <class H, class State>
void check_start(const H& h, const State& s, std::size_t index, Eigen::Index size) {
    const std::string who = "run_ensemble: start " + std::to_string(index);
    check_state(h, s, who.c_str());
    if (s.size() != size)
        throw invalid_argument(who + " has dimension " + std::to_string(s.size()) + " but the first start has " +
                               std::to_string(size) + "; expected one dimension for the whole ensemble");
    using std::isfinite;
    const double e = static_cast<double>(energy(h, s));
    if (!isfinite(e))
        throw invalid_argument(who + " has energy " + number_text(e) + "; expected a state of finite energy");
}

// The step of a lane that went non-finite during a chunk of k steps from
// `start` (step index `first`): replayed alone, one step at a time. Returns
// the 1-based step and leaves `start` at the last finite state. If the replay
// stays finite (it groups the steps differently, so it may differ by
// rounding), the chunk's last step is named.
template <class H, class State>
std::size_t replay_to_blow_up(const H& h, const table& m, State& start, std::size_t first, std::size_t k, double dt) {
    splitting_stepper<H, State> single(h, m);
    for (std::size_t j = 0; j < k; ++j) {
        State next = start;
        single.step(next, dt);
        if (!is_finite(next)) return first + j + 1;
        if (j + 1 < k) start = next;
    }
    return first + k;
}

// Lane `lane` of a state of batches (or of their dual numbers), as a plain state.
template <class State, class X>
State lane_state_of(const X& x, int lane) {
    State s(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        s.q[i] = lane_of(value_part(x.q[i]), lane);
        s.p[i] = lane_of(value_part(x.p[i]), lane);
    }
    return s;
}

// Trajectories start[0 .. count) (count <= L) advanced together in the lanes
// of one state; unused lanes carry a copy of lane 0 and are dropped.
template <int L, bool Tangent, class H, class State, class Reduction>
class lane_run {
    using S = lane_scalar<L>;
    using X = std::conditional_t<Tangent, phase_space<dual<S, 1>, State::dimension>, phase_space<S, State::dimension>>;
    using Scalar = typename X::scalar;
    using PlainVector = Eigen::Matrix<S, State::dimension, 1>;

public:
    lane_run(const H& h, const table& m, const State* start, int count, const ensemble_options& o,
             const Reduction& prototype, trajectory_result<State>* out)
        : h_(h), m_(m), count_(count), o_(o), out_(out), n_(start[0].size()), x_(n_), qv_(n_), pv_(n_),
          reductions_(std::size_t(count), prototype), stepper_(h, m) {
        for (int lane = 0; lane < L; ++lane) load_lane(lane, start[lane < count ? lane : 0]);
        // The tangent vector starts as the unit vector (1, ..., 1)/sqrt(2n).
        if constexpr (Tangent) {
            const double unit = 1 / std::sqrt(2.0 * double(n_));
            for (Eigen::Index i = 0; i < n_; ++i) x_.q[i].grad[0] = x_.p[i].grad[0] = S(unit);
        }
        const S energy0 = watch_energy_ ? energy_now() : S(0);
        for (int lane = 0; lane < count; ++lane) {
            alive_[lane] = true;
            e0_[lane] = lane_of(energy0, lane);
            scale_[lane] = e0_[lane] != 0 ? std::fabs(e0_[lane]) : 1;
            out_[lane].max_energy_error = o.energy ? 0 : -1;
            reductions_[std::size_t(lane)](start[lane], o.t0);
        }
    }

    // Chunks of sample_every steps; after each, every living lane is checked
    // and sampled, lost lanes refilled and the tangent vectors rescaled.
    void run() {
        X chunk_start = x_;
        std::size_t done = 0;
        int living = count_;
        while (done < o_.steps && living > 0) {
            const std::size_t k = std::min(o_.sample_every, o_.steps - done);
            chunk_start = x_;
            if (resume_) stepper_.resume_steps(x_, Scalar(o_.dt), k);
            else stepper_.steps(x_, Scalar(o_.dt), k);
            resume_ = true;
            done += k;
            S norm2(0);
            if constexpr (Tangent)
                for (Eigen::Index i = 0; i < n_; ++i)
                    norm2 += x_.q[i].grad[0] * x_.q[i].grad[0] + x_.p[i].grad[0] * x_.p[i].grad[0];
            if (sample(chunk_start, done, k, norm2)) living = refill_lost();
            if (living == 0) break;
            if constexpr (Tangent) rescale_tangent(norm2);
        }
        for (int lane = 0; lane < count_; ++lane) {
            if (alive_[lane]) out_[lane].final_state = lane_state(lane);
            if constexpr (!std::is_same_v<Reduction, no_reduction>)
                out_[lane].quantity = reductions_[std::size_t(lane)].value();
        }
    }

private:
    void load_lane(int lane, const State& s) {
        for (Eigen::Index i = 0; i < n_; ++i) {
            set_lane(value_part(x_.q[i]), lane, s.q[i]);
            set_lane(value_part(x_.p[i]), lane, s.p[i]);
        }
    }
    State lane_state(int lane) const { return lane_state_of<State>(x_, lane); }

    // The energy of every lane at once, from the plain state.
    S energy_now() {
        for (Eigen::Index i = 0; i < n_; ++i) {
            qv_[i] = value_part(x_.q[i]);
            pv_[i] = value_part(x_.p[i]);
        }
        return S(h_.kinetic(pv_)) + S(h_.potential(qv_));
    }

    // Checks and samples every living lane after a chunk of k steps ending at
    // step `done`; returns whether a lane was lost (non-finite or diverged).
    bool sample(const X& chunk_start, std::size_t done, std::size_t k, const S& norm2) {
        const double t = o_.t0 + double(done) * o_.dt;
        // A lane is finite when 0*x is 0 in every component (NaN otherwise).
        S probe(0);
        for (Eigen::Index i = 0; i < n_; ++i) {
            probe += value_part(x_.q[i]) * 0.0 + value_part(x_.p[i]) * 0.0;
            if constexpr (Tangent) probe += x_.q[i].grad[0] * 0.0 + x_.p[i].grad[0] * 0.0;
        }
        S e = watch_energy_ ? energy_now() : S(0);
        bool lost = false;
        for (int lane = 0; lane < count_; ++lane) {
            if (!alive_[lane]) continue;
            trajectory_result<State>& r = out_[lane];
            if (lane_of(probe, lane) != 0) {
                State last = lane_state_of<State>(chunk_start, lane);
                const std::size_t bad = replay_to_blow_up(h_, m_, last, done - k, k, o_.dt);
                r.stable = false;
                r.blowup_step = bad;
                r.blowup_time = o_.t0 + double(bad - 1) * o_.dt;
                r.failure = blow_up(bad, r.blowup_time, o_.dt).what();
                r.final_state = last;
                alive_[lane] = false;
                lost = true;
                continue;
            }
            if (watch_energy_) {
                const double err = std::fabs(lane_of(e, lane) - e0_[lane]) / scale_[lane];
                if (o_.energy) r.max_energy_error = std::max(r.max_energy_error, err);
                if (err > o_.divergence) {
                    r.stable = false;
                    r.blowup_step = done;
                    r.blowup_time = t - o_.dt;
                    r.failure = "the relative energy error reached " + number_text(err) + " > " +
                                number_text(o_.divergence) + " at step " + std::to_string(done) + " (t = " +
                                number_text(t) + ")";
                    r.final_state = lane_state(lane);
                    alive_[lane] = false;
                    lost = true;
                    continue;
                }
            }
            if constexpr (Tangent) {
                const double n2 = lane_of(norm2, lane);
                megno_[lane].add(t - o_.t0, 0.5 * std::log(n2) + log_offset_[lane]);
                r.megno = megno_[lane].mean();
            }
            if constexpr (!std::is_same_v<Reduction, no_reduction>) reductions_[std::size_t(lane)](lane_state(lane), t);
        }
        return lost;
    }

    // A lost lane carries a copy of a living one from now on (its numbers are
    // dropped); the stepper's carried force is then stale. Returns the living count.
    int refill_lost() {
        int living = 0, donor = -1;
        for (int lane = 0; lane < count_; ++lane)
            if (alive_[lane]) {
                ++living;
                if (donor < 0) donor = lane;
            }
        if (living == 0) return 0;
        const State d = lane_state(donor);
        for (int lane = 0; lane < L; ++lane)
            if (lane >= count_ || !alive_[lane]) {
                load_lane(lane, d);
                if constexpr (Tangent)
                    for (Eigen::Index i = 0; i < n_; ++i) {
                        set_lane(x_.q[i].grad[0], lane, lane_of(x_.q[i].grad[0], donor));
                        set_lane(x_.p[i].grad[0], lane, lane_of(x_.p[i].grad[0], donor));
                    }
            }
        resume_ = false;
        return living;
    }

    // |delta| grows like exp(lambda t) on chaotic orbits: divided by 2^400
    // (exactly) before it overflows, the factor kept in log_offset_.
    void rescale_tangent(const S& norm2) {
        bool rescaled = false;
        for (int lane = 0; lane < L; ++lane)
            if (lane_of(norm2, lane) > 1e200) {
                for (Eigen::Index i = 0; i < n_; ++i) {
                    set_lane(x_.q[i].grad[0], lane, std::ldexp(lane_of(x_.q[i].grad[0], lane), -400));
                    set_lane(x_.p[i].grad[0], lane, std::ldexp(lane_of(x_.p[i].grad[0], lane), -400));
                }
                if (lane < count_) log_offset_[lane] += 400 * std::log(2.0);
                rescaled = true;
            }
        if (rescaled) resume_ = false;  // the carried force's tangent part is stale
    }

    const H& h_;
    const table& m_;
    int count_;
    const ensemble_options& o_;
    trajectory_result<State>* out_;
    Eigen::Index n_;
    X x_;
    PlainVector qv_, pv_;
    std::array<bool, L> alive_{};
    std::array<double, L> e0_{}, scale_{};
    std::array<megno_accumulator<double>, L> megno_{};
    std::array<double, L> log_offset_{};  // ln of the factors the tangent vector was divided by
    std::vector<Reduction> reductions_;
    bool watch_energy_ = o_.energy || o_.divergence < std::numeric_limits<double>::infinity();
    splitting_stepper<H, X> stepper_;
    bool resume_ = false;
};

template <int L, bool Tangent, class H, class State, class Reduction>
void run_lanes(const H& h, const table& m, const State* start, int count, const ensemble_options& o,
               const Reduction& prototype, trajectory_result<State>* out) {
    lane_run<L, Tangent, H, State, Reduction>(h, m, start, count, o, prototype, out).run();
}

}  // namespace detail

// body(i) for i in [0, count) on `threads` OpenMP threads (0: OpenMP's
// default), dynamically scheduled (groups of chaotic or blown-up trajectories
// take different times); the first exception thrown by any call is rethrown
// after all have ended. Without OpenMP, in order on this thread.
template <class Body>
void for_each_in_parallel(std::size_t count, int threads, const Body& body) {
    std::exception_ptr error;
#ifdef _OPENMP
    const int team = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
#else
    (void)threads;
#endif
    for (long long g = 0; g < static_cast<long long>(count); ++g) {
        try {
            body(std::size_t(g));
        } catch (...) {
#ifdef _OPENMP
#pragma omp critical(sympl_ensemble_error)
#endif
            if (!error) error = std::current_exception();
        }
    }
    if (error) std::rethrow_exception(error);
}

// Trajectories [begin, end) of `starts` (begin a multiple of W, so that the
// batches are the same as in the whole run): results[i - begin] for start i.
// W = 1 runs one trajectory at a time (Hamiltonians that branch on the state).
template <int W = native_double_width, class H, class State, class Reduction = no_reduction>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
std::vector<trajectory_result<State>> run_ensemble_range(const H& h, const table& method, const std::vector<State>& starts,
                                                         std::size_t begin, std::size_t end, const ensemble_options& o,
                                                         const Reduction& reduction = {}) {
    detail::check_ensemble_options(o);
    if (begin > end || end > starts.size() || begin % W != 0)
        throw invalid_argument("run_ensemble_range: [" + std::to_string(begin) + ", " + std::to_string(end) + ") of " +
                               std::to_string(starts.size()) + " starts; expected a range inside, beginning at a multiple of " +
                               std::to_string(W));
    std::vector<trajectory_result<State>> results(end - begin);
    if (begin == end) return results;
    for (std::size_t i = begin; i < end; ++i) detail::check_start(h, starts[i], i, starts[begin].size());
    const std::size_t groups = (end - begin + W - 1) / W;
    for_each_in_parallel(groups, o.threads, [&](std::size_t g) {
        const std::size_t first = begin + g * W;
        const int count = int(std::min<std::size_t>(W, end - first));
        if (o.megno)
            detail::run_lanes<W, true>(h, method, &starts[first], count, o, reduction, &results[first - begin]);
        else
            detail::run_lanes<W, false>(h, method, &starts[first], count, o, reduction, &results[first - begin]);
    });
    return results;
}

// The whole ensemble, results in input order.
template <int W = native_double_width, class H, class State, class Reduction = no_reduction>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
std::vector<trajectory_result<State>> run_ensemble(const H& h, const table& method, const std::vector<State>& starts,
                                                   const ensemble_options& o, const Reduction& reduction = {}) {
    return run_ensemble_range<W>(h, method, starts, 0, starts.size(), o, reduction);
}

// Over a parameter of the Hamiltonian too: trajectory i runs make_hamiltonian(parameters[i])
// from starts[i], one trajectory at a time (each has its own Hamiltonian).
template <class MakeHamiltonian, class Parameter, class State, class Reduction = no_reduction>
auto run_parameter_ensemble(const MakeHamiltonian& make_hamiltonian, const std::vector<Parameter>& parameters,
                            const table& method, const std::vector<State>& starts, const ensemble_options& o,
                            const Reduction& reduction = {}) {
    detail::check_ensemble_options(o);
    if (parameters.size() != starts.size())
        throw invalid_argument("run_parameter_ensemble: " + std::to_string(parameters.size()) + " parameters for " +
                               std::to_string(starts.size()) + " starts; expected one parameter per start");
    std::vector<trajectory_result<State>> results(starts.size());
    for (std::size_t i = 0; i < starts.size(); ++i)
        detail::check_start(make_hamiltonian(parameters[i]), starts[i], i, starts.front().size());
    for_each_in_parallel(starts.size(), o.threads, [&](std::size_t i) {
        const auto h = make_hamiltonian(parameters[i]);
        if (o.megno)
            detail::run_lanes<1, true>(h, method, &starts[i], 1, o, reduction, &results[i]);
        else
            detail::run_lanes<1, false>(h, method, &starts[i], 1, o, reduction, &results[i]);
    });
    return results;
}

// MEGNO <Y> of one orbit over `steps` steps of dt, sampled every `sample_every`.
template <class H, class State>
double megno(const H& h, const table& method, const State& start, double dt, std::size_t steps,
             std::size_t sample_every = 1) {
    ensemble_options o;
    o.dt = dt;
    o.steps = steps;
    o.sample_every = sample_every;
    o.energy = false;
    o.megno = true;
    o.threads = 1;
    const auto r = run_ensemble<1>(h, method, std::vector<State>{start}, o);
    if (!r[0].stable) throw integration_error("megno: " + r[0].failure, r[0].blowup_step, r[0].blowup_time);
    return r[0].megno;
}

}  // namespace sympl
