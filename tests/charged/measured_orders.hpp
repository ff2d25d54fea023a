#pragma once
// The measured order of a charged particle's stepper from x0 over t_end, and
// the check that a list of tables reach their orders (within the house 0.15),
// for the tests of tests/charged/.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <utility>

#include <sympl/analysis/convergence.hpp>

namespace sympl::charged::testing {

// make() gives a fresh stepper; n steps of t_end / n from x0 (steps(x, dt, n) where the stepper has it).
template <class Make, class State>
order_measurement order_of(Make make, const State& x0, double t_end, std::size_t min_steps = 8) {
    return measure_order(
        [&](std::size_t n) {
            auto s = make();
            State x = x0;
            const double dt = t_end / double(n);
            if constexpr (requires { s.steps(x, dt, n); })
                s.steps(x, dt, n);
            else
                for (std::size_t i = 0; i < n; ++i) s.step(x, dt);
            return x;
        },
        t_end, {.min_steps = min_steps, .max_steps = 1 << 12, .floor = 1e-12});
}

// make(table name) gives a fresh stepper of that table.
template <class MakeFor, class State>
void check_orders(MakeFor make_for, const State& x0, double t_end,
                  std::initializer_list<std::pair<const char*, double>> tables) {
    for (const auto& entry : tables) {
        const std::string method_name = entry.first;
        const order_measurement m = order_of([&] { return make_for(method_name); }, x0, t_end);
        const double expected = entry.second, measured = m.order;
        CAPTURE(method_name);
        CAPTURE(measured);
        CHECK(m.converged);
        CHECK(std::abs(measured - expected) < 0.15);
    }
}

}  // namespace sympl::charged::testing
