#pragma once
// Equations of motion in first-order pair form, for the classic algorithms of
// Gould & Tobochnik (ch. 3) and Sandvik's lecture notes (classic_steppers.hpp):
//     dq/dt = dq_dt(q, p, t),   dp/dt = dp_dt(q, p, t).
// Newton's equations x'' = a(x, v, t) are the case q = x, p = v,
// dq_dt = v, dp_dt = a (Sandvik's lecture notes, "RK formulas for equations of motion");
// a separable Hamiltonian is the case dq_dt = dT/dp, dp_dt = -dV/dq
// (Gould & Tobochnik, eq. 3.73). Damping and driving enter through a(x, v, t).
#include <concepts>
#include <utility>

#include <Eigen/Core>

#include "hamiltonian.hpp"
#include "phase_space.hpp"
#include "quadratic_kinetic.hpp"

namespace sympl {

// A system a classic stepper can run on: writes dq/dt and dp/dt into `out`.
template <class E, class State>
concept equations_of_motion =
    phase_space_state<State> &&
    requires(const E& e, const typename State::vector& q, const typename State::vector& p, typename State::scalar t,
             typename State::vector& out) {
        e.dq_dt(q, p, t, out);
        e.dp_dt(q, p, t, out);
    };

// Newton's form: p is the velocity, dq/dt = p. The two-step leapfrog (eq. 3.47)
// and the damped leapfrog (Sandvik's lecture notes) exist only in this form.
template <class E>
concept newtonian_form = requires { requires E::p_is_velocity; };

// Newton's form with the force split as m a = F(x, t) - G(v) (Sandvik's lecture notes,
// "Leapfrog/Verlet method including damping"): `force` writes F, `drag` writes G.
template <class E, class State>
concept damped_newtonian_form =
    newtonian_form<E> && equations_of_motion<E, State> &&
    requires(const E& e, const typename State::vector& x, typename State::scalar t, typename State::vector& out) {
        { e.mass } -> std::convertible_to<double>;
        e.force(x, t, out);
        e.drag(x, out);
    };

// Whether dp/dt depends on p. When it does not, a stepper may reuse dp/dt
// across a change of p (velocity Verlet, the leapfrogs). A system says so with
// `static constexpr bool velocity_dependent = false;`; unknown means dependent.
template <class E>
constexpr bool force_depends_on_velocity() {
    if constexpr (requires { E::velocity_dependent; })
        return E::velocity_dependent;
    else
        return true;
}

// Newton's equations from an acceleration a(x, v, t), or a(x, t) when it does
// not depend on the velocity (then reused where the algorithms allow it).
template <class Acceleration, bool VelocityDependent>
struct newtonian {
    Acceleration acceleration;
    static constexpr bool p_is_velocity = true;
    static constexpr bool velocity_dependent = VelocityDependent;

    template <class Vec, class T>
    void dq_dt(const Vec&, const Vec& v, T, Vec& out) const { out = v; }
    template <class Vec, class T>
    void dp_dt(const Vec& x, const Vec& v, T t, Vec& out) const {
        if constexpr (VelocityDependent)
            out = acceleration(x, v, t);
        else
            out = acceleration(x, t);
    }
};

// make_newtonian([](const auto& x, const auto& v, auto t) { return -x - 0.1 * v; })
// make_newtonian([](const auto& x, auto t) { return -x; })   // velocity-independent
template <class Acceleration>
auto make_newtonian(Acceleration a) {
    constexpr bool two_arguments = requires(const Acceleration& f, const Eigen::VectorXd& x) { f(x, 0.0); };
    return newtonian<Acceleration, !two_arguments>{std::move(a)};
}

// Hamilton's equations of a separable Hamiltonian (Gould & Tobochnik eq. 3.73) in pair form.
// A generic T quadratic in p is recognised once per dimension
// (quadratic_kinetic.hpp), as the splitting steppers do: dq/dt is then
// M^-1 p, not a gradient of T at every evaluation.
template <class H, class Vec = Eigen::VectorXd>
struct hamilton_equations {
    H hamiltonian;
    static constexpr bool velocity_dependent = false;  // dp/dt = -dV/dq(q) never depends on p
    mutable quadratic_kinetic<Vec> kinetic;  // what T was found to be, for the last dimension

    template <class V, class T>
    void dq_dt(const V&, const V& p, T, V& out) const {
        if constexpr (std::same_as<V, Vec>) recognised_velocity(hamiltonian, kinetic, p, out);
        else velocity(hamiltonian, p, out);
    }
    template <class V, class T>
    void dp_dt(const V& q, const V&, T, V& out) const { force(hamiltonian, q, out); }
};

// The equations of motion of `system`: itself when it already is one, Hamilton's
// equations when it is a separable Hamiltonian.
template <class State, class System>
auto equations_of(System system) {
    if constexpr (equations_of_motion<System, State>)
        return system;
    else
        return hamilton_equations<System, typename State::vector>{std::move(system), {}};
}

}  // namespace sympl
