#pragma once
// A stepper's own interpolation inside its last accepted step, moved along a
// run with the interface of step_interpolant (hermite_interpolant.hpp), so
// that dense output and events (dense_output.hpp, events.hpp) take either.
// rkn_pair_stepper is such a stepper: dprkn6 by its published continuous
// extension, dprkn8 and dprkn12 by a partial step of the pair itself
// (methods/rkn_pairs.hpp; docs/dense-output.md says which pair has what).
#include <concepts>
#include <cstdint>

namespace sympl {

// interpolate(theta, out): the state at t + theta dt inside the last step the
// stepper took or accepted, 0 <= theta <= 1; its forces counted apart.
template <class S>
concept interpolating_stepper = requires(S& s, typename S::scalar theta, typename S::state_type& out) {
    s.interpolate(theta, out);
    { s.interpolation_force_evaluations() } -> std::convertible_to<std::uint64_t>;
};

// start(x, t) at the first state, push(x, t) right after every step, before
// the stepper takes the next one (it interpolates its last step only).
template <interpolating_stepper Stepper>
class stepper_interpolant {
public:
    using State = typename Stepper::state_type;
    using scalar = typename Stepper::scalar;

    explicit stepper_interpolant(Stepper& s) : s_(s), forces0_(s.interpolation_force_evaluations()) {}

    void start(const State& x, scalar t) {
        x0_ = x1_ = x;
        t0_ = t1_ = t;
    }
    void push(const State& x, scalar t) {
        std::swap(x0_, x1_);
        x1_ = x;
        t0_ = t1_;
        t1_ = t;
    }
    scalar t0() const { return t0_; }
    scalar t1() const { return t1_; }

    void evaluate(scalar t, State& out) {
        if (t == t1_) out = x1_;
        else if (t == t0_) out = x0_;
        else evaluate_fraction((t - t0_) / (t1_ - t0_), out);
    }
    // At t0 + th (t1 - t0): th = 0 and 1 give the end states exactly.
    void evaluate_fraction(scalar th, State& out) {
        if (th == scalar(1)) out = x1_;
        else if (th == scalar(0)) out = x0_;
        else s_.interpolate(th, out);
    }

    std::uint64_t force_evaluations() const { return s_.interpolation_force_evaluations() - forces0_; }
    std::uint64_t velocity_evaluations() const { return 0; }

private:
    Stepper& s_;
    State x0_, x1_;
    scalar t0_{}, t1_{};
    std::uint64_t forces0_;
};

}  // namespace sympl
