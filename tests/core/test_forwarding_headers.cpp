// The pre-0.2 include paths (<sympl/table.hpp>, ...) still work: each is a
// forwarding header to its new folder (docs/layout.md), removed in 0.3. All of
// them but ensemble_mpi.hpp (Boost.MPI) are included here, without their note.
#define SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#include <doctest/doctest.h>

#include <type_traits>

#include <sympl/adaptive.hpp>
#include <sympl/batch.hpp>
#include <sympl/catalog.hpp>
#include <sympl/chaos_indicator.hpp>
#include <sympl/classic_steppers.hpp>
#include <sympl/convergence.hpp>
#include <sympl/dual.hpp>
#include <sympl/ensemble.hpp>
#include <sympl/equations_of_motion.hpp>
#include <sympl/error.hpp>
#include <sympl/extrapolation.hpp>
#include <sympl/hamiltonian.hpp>
#include <sympl/integrate.hpp>
#include <sympl/odeint.hpp>
#include <sympl/order_conditions.hpp>
#include <sympl/phase_space.hpp>
#include <sympl/phase_space_measures.hpp>
#include <sympl/poincare_section.hpp>
#include <sympl/processing.hpp>
#include <sympl/richardson.hpp>
#include <sympl/splitting_stepper.hpp>
#include <sympl/table.hpp>
#include <sympl/table_order.hpp>
#include <sympl/time_transformation.hpp>

#include <sympl/core/splitting_stepper.hpp>
#include <sympl/core/table.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/methods/catalog.hpp>

TEST_CASE("forwarding headers: the old include paths reach the same catalog and stepper") {
    // One header behind two paths: the same types, not look-alikes.
    static_assert(std::is_same_v<decltype(sympl::method("leapfrog_kdk")), const sympl::table&>);
    using State = sympl::phase_space<double, 1>;
    using Stepper = sympl::splitting_stepper<sympl::hamiltonians::harmonic_oscillator, State>;
    static_assert(std::is_same_v<Stepper::state_type, State>);

    const sympl::table& leapfrog = sympl::method("leapfrog_kdk");
    CHECK(leapfrog.order() == 2);
    // One kick-drift-kick step on the oscillator from (1, 0): q1 = 1 - h^2/2.
    Stepper stepper({}, leapfrog);
    State x(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
    stepper.step(x, 0.1);
    CHECK(x.q[0] == doctest::Approx(1 - 0.005).epsilon(1e-15));
}
