#pragma once
// The kind for planetary systems (run_kind<wisdom_holman>): the method's table
// run as a Wisdom-Holman splitting (planetary/wisdom_holman_stepper.hpp), its drifts the
// exact Kepler flows about the star, its kicks the planets' interaction, in
// democratic heliocentric or Jacobi coordinates that the stepper keeps between
// steps (a checkpoint holds them as the stepper's carried list), with the corrector, kernel and coordinates the method names
// (wh(<table>, corrector = K, kernel = ..., coordinates = ...)).
#include "running/run_context.hpp"

namespace sympl::app::detail {

template <>
struct run_kind<method_kind::wisdom_holman> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return c.drive(
            make_wisdom_holman<typename C::State>(c.sys, *c.m.coefficients, wisdom_holman_options_of(c.m)));
    }
};

}  // namespace sympl::app::detail
