#pragma once
// Boost.Odeint interop, both ways.
//
//  - odeint_system{h}: a sympl Hamiltonian as an Odeint system in first-order
//    form, x = (q, p) stacked in any contiguous container (std::vector<S>,
//    std::array), for runge_kutta4, runge_kutta_dopri5 (controlled and dense
//    output), runge_kutta_fehlberg78 and the rest.
//  - odeint_symplectic_system(h): the pair (dq/dt from p, dp/dt from q) that
//    Odeint's symplectic_rkn_* steppers take.
//  - odeint_stepper: any sympl stepper (a table's splitting_stepper, a classic
//    stepper) where Odeint expects a stepper, so integrate_const /
//    integrate_n_steps with an Odeint observer run it on phase_space states.
//    The stepper carries its own system, so the system argument Odeint passes
//    is ignored (pass sympl::odeint_stepper_system{}).
//  - stacked / from_stacked (phase_space.hpp) convert between the two state forms.
#include <cstddef>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "error.hpp"
#include "hamiltonian.hpp"
#include "integrate.hpp"
#include "phase_space.hpp"
#include "splitting_stepper.hpp"

namespace sympl {

namespace detail {
template <class Container>
using element_of = std::decay_t<decltype(*std::data(std::declval<Container&>()))>;

}  // namespace detail

// dx/dt = (dT/dp, -dV/dq) for Odeint. Dim fixes the number of degrees of freedom
// at compile time (no allocation per call); Eigen::Dynamic reads it from x.
template <class H, int Dim = Eigen::Dynamic>
struct odeint_system {
    H hamiltonian;

    template <class Container, class T>
    void operator()(const Container& x, Container& dxdt, T /*t*/) const {
        using S = detail::element_of<Container>;
        using Vec = Eigen::Matrix<S, Dim, 1>;
        const auto n = static_cast<Eigen::Index>(std::size(x) / 2);
        const Eigen::Map<const Vec> q(std::data(x), n), p(std::data(x) + n, n);
        Vec v(n), f(n);
        velocity(hamiltonian, Vec(p), v);
        force(hamiltonian, Vec(q), f);
        Eigen::Map<Vec>(std::data(dxdt), n) = v;
        Eigen::Map<Vec>(std::data(dxdt) + n, n) = f;
    }
};

template <int Dim = Eigen::Dynamic, class H>
odeint_system<H, Dim> make_odeint_system(H h) {
    return {std::move(h)};
}

// The (coordinate, momentum) pair for Odeint's symplectic_rkn steppers:
// first(p, dqdt) writes dT/dp, second(q, dpdt) writes -dV/dq.
template <int Dim = Eigen::Dynamic, class H>
auto odeint_symplectic_system(H h) {
    const auto rate = [](const auto& fn) {
        return [fn](const auto& in, auto& out) {
            using S = detail::element_of<std::decay_t<decltype(in)>>;
            using Vec = Eigen::Matrix<S, Dim, 1>;
            const auto n = static_cast<Eigen::Index>(std::size(in));
            Vec r(n);
            fn(Vec(Eigen::Map<const Vec>(std::data(in), n)), r);
            Eigen::Map<Vec>(std::data(out), n) = r;
        };
    };
    return std::make_pair(rate([h](const auto& p, auto& v) { velocity(h, p, v); }),
                          rate([h](const auto& q, auto& f) { force(h, q, f); }));
}

// The system argument for odeint_stepper (ignored: the stepper has its own).
struct odeint_stepper_system {};

template <fixed_step_stepper Stepper>
class odeint_stepper {
public:
    using state_type = typename Stepper::state_type;
    using deriv_type = state_type;
    using value_type = typename Stepper::scalar;
    using time_type = value_type;
    using order_type = unsigned short;
    using stepper_category = boost::numeric::odeint::stepper_tag;

    odeint_stepper(Stepper stepper, order_type order) : stepper_(std::move(stepper)), order_(order) {}

    order_type order() const { return order_; }

    template <class System>
    void do_step(System&&, state_type& x, time_type t, time_type dt) {
        detail::one_step(stepper_, x, t, dt);
    }

    Stepper& stepper() { return stepper_; }
    const Stepper& stepper() const { return stepper_; }

private:
    Stepper stepper_;
    order_type order_;
};

// A splitting stepper for Odeint, its order from the table.
template <class H, class State>
odeint_stepper<splitting_stepper<H, State>> make_odeint_stepper(splitting_stepper<H, State> s) {
    const auto order = static_cast<unsigned short>(s.method().order());
    return {std::move(s), order};
}

// The flow of Odeint's runge_kutta4 on H, n steps of dt, as a callable on
// phase_space states of any scalar (double, or dual numbers to differentiate
// the numerical flow: phase_space_measures.hpp).
template <int Dim = Eigen::Dynamic, class H>
auto odeint_rk4_flow(H h, double dt, std::size_t n) {
    return [h = std::move(h), dt, n](auto& x) {
        using State = std::decay_t<decltype(x)>;
        using S = typename State::scalar;
        using Container = std::vector<S>;
        std::vector<S> y = stacked(x);
        boost::numeric::odeint::runge_kutta4<Container, double, Container, double> rk4;
        boost::numeric::odeint::integrate_n_steps(rk4, odeint_system<H, Dim>{h}, y, 0.0, dt, n);
        x = from_stacked<State>(y);
    };
}

}  // namespace sympl
