#pragma once
// The kinds for any Hamiltonian H(q, p), separable or not (run_kind<gauss>,
// <tao>, <semiexplicit>): the implicit Gauss-Legendre collocation
// (gauss_collocation.hpp) and the two extended-phase-space methods
// (extended_phase_space.hpp, semiexplicit.hpp), composed by the method's table. A separable
// Hamiltonian runs them too: Gauss-Legendre takes it as it is, the others as
// separable_as_general (dH/dq = -F(q), dH/dp = dT/dp).
#include <utility>

#include "running/run_context.hpp"

namespace sympl::app::detail {

// The system as the extended-phase-space steppers take it.
template <class Sys>
auto as_general(const Sys& sys) {
    if constexpr (general_hamiltonian<Sys, phase_space<double>::vector>)
        return sys;
    else
        return separable_as_general<Sys>{sys};
}

// Gauss-Legendre with the member's stages s, order 2s: the last step's stage
// values, its mode and frozen Newton Jacobian are carried from step to step
// (a checkpoint holds them as the stepper's carried list).
template <>
struct run_kind<method_kind::gauss> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return c.drive(
            gauss_collocation_stepper<typename C::system, typename C::State>(c.sys, c.m.parameters.stages));
    }
};

// Tao (2016): its second copy is carried from step to step (a checkpoint
// holds it as the stepper's carried list); omega from the scene, or 4 times
// the fastest frequency at the start.
template <>
struct run_kind<method_kind::tao> {
    template <class C>
    static steps_and_forces run(const C& c) {
        auto h = as_general(c.sys);
        tao_options o = tao_options_for(h, c.x);  // binding in the start's units
        if (c.m.omega) o.omega = *c.m.omega;
        return c.drive(tao_stepper<decltype(h), typename C::State>(std::move(h), *c.m.coefficients, o));
    }
};

// Jayawardana & Ohsawa (2023): both copies start at the state every step.
template <>
struct run_kind<method_kind::semiexplicit> {
    template <class C>
    static steps_and_forces run(const C& c) {
        auto h = as_general(c.sys);
        return c.drive(semiexplicit_stepper<decltype(h), typename C::State>(std::move(h), *c.m.coefficients));
    }
};

}  // namespace sympl::app::detail
