#include <doctest/doctest.h>

#include <cmath>

#include <sympl/sympl.hpp>

using namespace sympl;

TEST_CASE("measure_order sees a kick/drift swap that the harmonic oscillator cannot") {
    // McLachlan-Atela order 4 read with its letters swapped (drifts taken as
    // kicks): the measured order drops to 3 on the pendulum.
    const table& ma4 = method("mclachlan_atela_4");
    const table swapped("swapped", ma4.drift(), ma4.kick());
    CHECK(std::fabs(measure_order(ma4, order_problem::pendulum).order - 4) <= 0.15);
    CHECK(measure_order(swapped, order_problem::pendulum).order < 3.5);
    CHECK(measure_order(swapped, order_problem::kepler).order < 3.5);
}

TEST_CASE("measure_order reports the slopes it read") {
    const order_measurement m = measure_order(method("leapfrog_kdk"), order_problem::kepler);
    CHECK(m.converged);
    CHECK(m.dt.size() >= m.difference.size());
    CHECK(m.difference.size() >= 3);
    for (std::size_t k = 1; k < m.dt.size(); ++k) CHECK(m.dt[k] == doctest::Approx(m.dt[k - 1] / 2));
}
