#pragma once
// The charged kind (run_kind<charged>) on a system that is a charged particle
// in a field (its particle() and electromagnetic_field(); charged_particle, charged_uniform):
// the pushers on the kinetic state (x, v), converted from the system's
// canonical (q, p) once per group of steps and back, and the splittings on
// (q, p) itself (sympl/charged/). The fields of the program's systems are
// static, so the steppers need no time.
#include <cmath>
#include <cstdint>
#include <utility>

#include "running/run_context.hpp"

namespace sympl::app::detail {

// A stepper of sympl/charged/ as the drivers take it: no velocity count of its own.
template <class Stepper>
struct charged_run : Stepper {
    using Stepper::Stepper;
    std::uint64_t velocity_evaluations() const { return 0; }
};

// A pusher over the canonical state of Dim degrees of freedom: v (or u = gamma v)
// = (p - e A(q)) / m in, p = m v + e A(q) back.
template <class Pusher, int Dim>
class pushed_on_canonical {
public:
    using state_type = phase_space<double, Dim>;
    using scalar = double;

    explicit pushed_on_canonical(Pusher p) : pusher_(std::move(p)) {}
    std::uint64_t force_evaluations() const { return pusher_.force_evaluations(); }
    std::uint64_t velocity_evaluations() const { return 0; }

    void step(state_type& x, double dt) { steps(x, dt, 1); }
    void steps(state_type& x, double dt, std::size_t n) {
        const charged::particle& a = pusher_.charged_particle();
        charged::kinetic_state<> k;
        k.q.setZero();
        k.q.template head<Dim>() = x.q;
        k.p.setZero();
        k.p.template head<Dim>() = (x.p - a.charge * charged::vec3<>(pusher_.field().A(k.q)).template head<Dim>()) / a.mass;
        for (std::size_t i = 0; i < n; ++i) pusher_.step(k, dt);
        x.q = k.q.template head<Dim>();
        x.p = (a.mass * k.p + a.charge * charged::vec3<>(pusher_.field().A(k.q))).template head<Dim>();
    }

private:
    Pusher pusher_;
};

template <>
struct run_kind<method_kind::charged> {
    template <class C>
    static steps_and_forces run(const C& c) {
        constexpr int Dim = C::dimension;
        const charged::particle a = c.sys.particle();
        const auto f = c.sys.electromagnetic_field();
        using F = std::decay_t<decltype(f)>;
        const bool newtonian = std::isinf(a.speed_of_light);
        const auto newton_only = [&] {
            if (!newtonian)
                throw invalid_argument("method '" + c.m.name +
                                       "' needs Newton's motion; this system is relativistic (speed_of_light = " +
                                       std::to_string(a.speed_of_light) + "; use boris(relativistic = true))");
        };
        switch (c.m.parameters.scheme) {
        case charged_scheme::boris:
            newton_only();
            return c.drive(pushed_on_canonical<charged::boris_stepper<F>, Dim>(charged::boris_stepper<F>(a, f)));
        case charged_scheme::relativistic:
            return c.drive(
                pushed_on_canonical<charged::relativistic_pusher<F>, Dim>(charged::relativistic_pusher<F>(a, f)));
        case charged_scheme::cartesian_split:
            newton_only();
            return c.drive(charged_run<charged::canonical_splitting_stepper<F, Dim>>(a, f, *c.m.coefficients));
        case charged_scheme::cylindrical_split:
            newton_only();
            if constexpr (charged::axisymmetric_potentials<F>)
                return c.drive(charged_run<charged::axisymmetric_splitting_stepper<F, Dim>>(a, f, *c.m.coefficients));
            else
                throw invalid_argument("method '" + c.m.name +
                                       "' needs a field symmetric about the z axis (charged_particle's); this "
                                       "system's is not (use cartesian_split(<table>))");
        }
        throw std::logic_error("method '" + c.m.name + "': a charged scheme without its run");
    }
};

}  // namespace sympl::app::detail
