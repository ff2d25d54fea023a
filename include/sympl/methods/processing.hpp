#pragma once
// Processed methods: a cheap kernel K applied every step, and a processor P
// applied only where the state is looked at. The method P o K^n o P^-1 has a
// higher (effective) order than K itself, at the cost of K alone in a long
// run (Blanes, Casas & Ros 1999, SIAM J. Sci. Comput. 21, 711; Blanes 2001,
// Appl. Numer. Math. 37, 289; Blanes, Casas & Murua 2006, SIAM J. Sci. Comput.
// 27, 1817). The processor is a composition whose kick and drift weights each
// sum to zero: a near-identity change of variables, not a step in time.
//
// processed_stepper keeps every output at the true state: the state it is
// given and returns is x; the kernel runs on y = P^-1(x), kept inside the
// stepper and reused while the caller hands back the x it returned.
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/carried_in_place.hpp"
#include "../core/carried_state.hpp"
#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/phase_space.hpp"
#include "../core/splitting_stepper.hpp"
#include "../core/table.hpp"

namespace sympl {

struct processed_method {
    std::string name;
    table kernel;                     // the step taken every time
    std::vector<substep> processor;   // P, in order of application: kernel state -> true state
    int order = 0;                    // effective order of P o K^n o P^-1 (the kernel's own is lower)
    std::string citation;
    std::string family = "processed";
};

// P^-1: the processor's sub-steps backwards with opposite weights.
inline std::vector<substep> inverse(const std::vector<substep>& processor) {
    std::vector<substep> ops(processor.rbegin(), processor.rend());
    for (substep& s : ops) s.weight = -s.weight;
    return ops;
}

// A processed method whose kernel is `kernel` and whose processor is `base`
// taken with the step fractions `weights` (in order of application; they must
// sum to 0, so that P is near the identity). Throws invalid_table with the
// offending value.
inline processed_method make_processed(std::string name, table kernel, const table& base,
                                       const std::vector<coefficient>& weights, int order, std::string citation) {
    if (weights.empty())
        throw invalid_table("processed method '" + name + "': no processor weights; expected at least two summing to 0");
    coefficient sum = 0, largest = 0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        if (!std::isfinite(weights[i]))
            throw invalid_table("processed method '" + name + "': processor weight[" + std::to_string(i) + "] = " +
                                detail::format_coefficient(weights[i]) + "; expected a finite number");
        sum += weights[i];
        largest = std::max(largest, std::fabs(weights[i]));
    }
    if (std::fabs(sum) > 1e-14L * std::max<coefficient>(1, largest))
        throw invalid_table("processed method '" + name + "': processor weights sum to " + detail::format_coefficient(sum) +
                            "; expected 0 (a processor is a change of variables, not a step in time)");
    if (base.has_force_gradient())
        throw invalid_table("processed method '" + name + "': processor base '" + base.name() +
                            "' has force-gradient kicks; expected a plain kick-drift table");
    std::vector<substep> ops;
    for (coefficient w : weights) detail::append_scaled(ops, base, w);
    return {std::move(name), std::move(kernel), detail::canonical(std::move(ops)), order, std::move(citation)};
}

// Runs a processed_method. Same calls as splitting_stepper (step, steps,
// resume_steps, counters), so the drivers of fixed_step.hpp and their observers
// work unchanged and see the true state. The kernel's state is reused while
// the caller passes back, bit for bit, the state the last call returned and
// the same dt; otherwise P^-1 is applied afresh (P depends on dt). Each call
// applies P once: n steps in one call cost n kernel steps and one processing.
template <class H, class State>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
class processed_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    processed_stepper(H hamiltonian, processed_method method, stepper_options options = {})
        : kernel_(std::move(hamiltonian), method.kernel, options), method_(std::move(method)),
          pre_(inverse(method_.processor)) {}

    void step(State& x, scalar dt) { steps(x, dt, 1); }

    void steps(State& x, scalar dt, std::size_t n) {
        using std::isfinite;
        if (!isfinite(dt) || dt == scalar(0))
            throw invalid_argument("processed_stepper: dt = " + std::to_string(static_cast<double>(primal(dt))) +
                                   "; expected a finite non-zero step size");
        check_state(kernel_.hamiltonian(), x, "processed_stepper");
        const bool same = carried_ && dt == dt_ && x.q.size() == returned_.q.size() &&
                          (x.q.array() == returned_.q.array()).all() && (x.p.array() == returned_.p.array()).all();
        if (same) {
            kernel_.resume_steps(y_, dt, n);
        } else {
            y_ = x;
            apply(y_, pre_, dt);
            kernel_.steps(y_, dt, n);
        }
        x = y_;
        apply(x, method_.processor, dt);
        returned_ = x;
        dt_ = dt;
        carried_ = true;
    }

    // The driver's call between chunks: the same as steps() (whether the
    // kernel's state carries over is decided by comparing x).
    void resume_steps(State& x, scalar dt, std::size_t n) { steps(x, dt, n); }

    // Kernel and processing together.
    std::uint64_t force_evaluations() const { return kernel_.force_evaluations() + processing_forces_; }
    std::uint64_t velocity_evaluations() const { return kernel_.velocity_evaluations() + processing_velocities_; }
    void reset_counters() {
        kernel_.reset_counters();
        processing_forces_ = processing_velocities_ = 0;
    }

    // The kernel's state behind the last x returned.
    const State& kernel_state() const { return y_; }

    // What the stepper carries between calls (the kernel's state and its
    // memory, the x it returned last and its dt): a stepper of the same H and
    // method given restore_carried(carried()) and handed that x goes on bit
    // for bit (a checkpoint). The counters are not carried. Restored in place
    // (carried_in_place.hpp): the stepper holds the caller's H.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar>
    {
        return detail::carried_list<scalar>(*this);
    }
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar>
    {
        detail::restore_carried_in_place<scalar>(*this, values, "processed_stepper");
    }
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.carried_);
        l.number(self.dt_);
        auto& y = self.y_;
        auto& x = self.returned_;
        stepper_memory<vector> m = self.kernel_.memory();  // its counters stay
        for (auto* v : {&y.q, &y.p, &x.q, &x.p}) l.numbers(*v);
        for (auto* v : {&m.force, &m.velocity, &m.q_error, &m.p_error}) l.numbers(*v);
        l.flag(m.force_fresh);
        l.flag(m.velocity_fresh);
        l.check(y.p.size() == y.q.size() && x.q.size() == y.q.size() && x.p.size() == y.q.size(),
                "holds states of different sizes");
        if constexpr (!std::is_const_v<Self>) self.kernel_.restore(m);
    }
    const H& hamiltonian() const { return kernel_.hamiltonian(); }
    const processed_method& method() const { return method_; }

private:
    // The sub-steps one by one: the processor is applied once per call, so a
    // plain walk costs nothing that matters.
    void apply(State& x, const std::vector<substep>& ops, scalar dt) {
        if (f_.size() != x.q.size()) f_.resize(x.q.size()), v_.resize(x.q.size());
        for (const substep& s : ops) {
            const scalar h = static_cast<scalar>(s.weight) * dt;
            if (s.kind == substep::kick) {
                force(kernel_.hamiltonian(), x.q, f_);
                x.p += h * f_;
                ++processing_forces_;
            } else {
                velocity(kernel_.hamiltonian(), x.p, v_);
                x.q += h * v_;
                ++processing_velocities_;
            }
        }
    }

    splitting_stepper<H, State> kernel_;
    processed_method method_;
    std::vector<substep> pre_;  // P^-1
    State y_{}, returned_{};
    vector f_{}, v_{};
    scalar dt_{};
    bool carried_ = false;
    std::uint64_t processing_forces_ = 0, processing_velocities_ = 0;
};

}  // namespace sympl
