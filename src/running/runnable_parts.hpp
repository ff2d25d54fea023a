#pragma once
// What a Hamiltonian offers the program beside its runs (runnable_system.hpp): a
// long-double reference, ensembles and Poincare sections, each a function of
// the system's type. runnable.hpp builds them for a system's own type where its
// registry entry asks (ensembles); generic_path.cpp builds them once for the
// type-erased systems, which serve every other system.
#include <utility>
#include <vector>

#include "running/run_context.hpp"

namespace sympl::app::detail {

// A reference run in long double by the stepper make(sys) returns.
template <class Sys, class MakeStepper>
reference_function long_double_reference(Sys sys, MakeStepper make) {
    return [sys = std::move(sys), make](double t0, double t_end, double dt, const std::vector<double>& x) {
        using L = phase_space<long double>;
        L y = from_stacked<L>(x);
        auto stepper = make(sys);
        integrate_until(stepper, y, (long double)t0, (long double)t_end, (long double)dt);
        return to_vector(y);
    };
}

// Sofroniou-Spaletta 10 in long double: the reference of a separable H.
template <class Sys>
reference_function reference_by_splitting(Sys sys) {
    return long_double_reference(std::move(sys), [](const Sys& s) {
        return splitting_stepper<Sys, phase_space<long double>>(s, method("sofroniou_spaletta_10"));
    });
}
inline constexpr const char* splitting_reference_method = "sofroniou_spaletta_10, long double";

// Gauss-Legendre of order 6 in long double: symplectic for any H(q, p).
template <class Sys>
reference_function reference_by_gauss(Sys sys) {
    return long_double_reference(std::move(sys), [](const Sys& s) {
        return gauss_collocation_stepper<Sys, phase_space<long double>>(s, 3);
    });
}
inline constexpr const char* gauss_reference_method = "gauss_6, long double";

// Equations of motion only: RK4 in double.
template <class Sys>
reference_function reference_by_rk4(Sys sys) {
    return [sys = std::move(sys)](double t0, double t_end, double dt, const std::vector<double>& x) {
        using State = phase_space<double>;
        State y = from_stacked<State>(x);
        auto s4 = make_classic<rk4, State>(sys);
        integrate_until(s4, y, t0, t_end, dt);
        return to_vector(y);
    };
}

// An ensemble of a separable H on states of Dim degrees of freedom, W
// trajectories a step in SIMD lanes (parallel/ensemble.hpp).
template <int Dim, int W, class Sys>
ensemble_function ensemble_of(Sys sys) {
    return [sys = std::move(sys)](const ensemble_request& rq, const std::vector<std::vector<double>>& starts) {
        using S = state_of<Dim>;
        std::vector<S> states;
        states.reserve(starts.size());
        for (const auto& x : starts) states.push_back(from_stacked<S>(x));
        const ensemble_options o{.t0 = rq.t0, .dt = rq.dt, .steps = rq.steps, .sample_every = rq.sample_every,
                                 .divergence = rq.divergence, .megno = rq.megno, .threads = rq.threads};
        std::vector<ensemble_row> rows;
        rows.reserve(starts.size());
        for (const auto& r : run_ensemble<W>(sys, *rq.method, states, o))
            rows.push_back({r.stable, r.blowup_step, r.blowup_time, r.failure, r.max_energy_error, r.megno,
                            to_vector(r.final_state)});
        return rows;
    };
}

// Upward crossings of q1 = 0 by a splitting table (analysis/poincare_section.hpp).
template <int Dim, class Sys>
section_function section_of(Sys sys) {
    return [sys = std::move(sys)](const table& m, double dt, std::size_t steps, const std::vector<double>& x0) {
        using S = state_of<Dim>;
        splitting_stepper<Sys, S> stepper(sys, m);
        std::vector<std::vector<double>> points;
        for (const S& c : section_crossings(stepper, from_stacked<S>(x0), dt, steps)) points.push_back(to_vector(c));
        return points;
    };
}

}  // namespace sympl::app::detail
