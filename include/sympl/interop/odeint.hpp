#pragma once
// Boost.Odeint interop, both ways.
//
//  - odeint_system{h}: a sympl Hamiltonian (or any equations of motion) as an
//    Odeint system in first-order form, x = (q, p) stacked in any contiguous
//    container (std::vector<S>, std::array), for runge_kutta4,
//    runge_kutta_dopri5 (controlled and dense output), runge_kutta_fehlberg78
//    and the rest; with an odeint_workspace it allocates nothing and counts
//    its evaluations.
//  - odeint_symplectic_system(h): the pair (dq/dt from p, dp/dt from q) that
//    Odeint's symplectic_rkn_* steppers take.
//  - odeint_stepper: any sympl stepper (a table's splitting_stepper, a classic
//    stepper) where Odeint expects a stepper, so integrate_const /
//    integrate_n_steps with an Odeint observer run it on phase_space states.
//    The stepper carries its own system, so the system argument Odeint passes
//    is ignored (pass sympl::odeint_stepper_system{}).
//  - stacked / from_stacked (phase_space.hpp) convert between the two state forms.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../drivers/fixed_step.hpp"
#include "../core/phase_space.hpp"
#include "../core/splitting_stepper.hpp"

namespace sympl {

namespace detail {
template <class Container>
using element_of = std::decay_t<decltype(*std::data(std::declval<Container&>()))>;

}  // namespace detail

// Scratch vectors for odeint_system, and a count of its evaluations. Odeint
// copies the system at every step, so the scratch lives outside it: with a
// workspace, evaluations on dynamic-size states allocate nothing.
template <class S, int Dim = Eigen::Dynamic>
struct odeint_workspace {
    Eigen::Matrix<S, Dim, 1> q, p, dq, dp;
    std::uint64_t evaluations = 0;
};

// dx/dt for Odeint, x = (q, p) stacked: (dT/dp, -dV/dq) for a separable
// Hamiltonian, (dq_dt, dp_dt) at time t for any other equations of motion
// (equations_of_motion.hpp: damped, driven, Newton's form). Dim fixes the
// number of degrees of freedom at compile time (no allocation per call);
// Eigen::Dynamic reads it from x and allocates unless a workspace is given.
template <class H, int Dim = Eigen::Dynamic>
struct odeint_system {
    H hamiltonian;  // or equations of motion
    odeint_workspace<double, Dim>* workspace = nullptr;

    template <class Container, class T>
    void operator()(const Container& x, Container& dxdt, T t) const {
        using S = detail::element_of<Container>;
        using Vec = Eigen::Matrix<S, Dim, 1>;
        const auto n = static_cast<Eigen::Index>(std::size(x) / 2);
        if constexpr (std::is_same_v<S, double>) {
            if (workspace) {
                ++workspace->evaluations;
                return evaluate(x, dxdt, t, n, workspace->q, workspace->p, workspace->dq, workspace->dp);
            }
        }
        Vec q(n), p(n), dq(n), dp(n);
        evaluate(x, dxdt, t, n, q, p, dq, dp);
    }

private:
    template <class Container, class T, class Vec>
    void evaluate(const Container& x, Container& dxdt, T t, Eigen::Index n, Vec& q, Vec& p, Vec& dq, Vec& dp) const {
        q = Eigen::Map<const Vec>(std::data(x), n);
        p = Eigen::Map<const Vec>(std::data(x) + n, n);
        using S = typename Vec::Scalar;
        if constexpr (requires { hamiltonian.dq_dt(q, p, S(t), dq); }) {  // equations of motion
            hamiltonian.dq_dt(q, p, S(t), dq);
            hamiltonian.dp_dt(q, p, S(t), dp);
        } else {
            velocity(hamiltonian, p, dq);
            force(hamiltonian, q, dp);
        }
        Eigen::Map<Vec>(std::data(dxdt), n) = dq;
        Eigen::Map<Vec>(std::data(dxdt) + n, n) = dp;
    }
};

template <int Dim = Eigen::Dynamic, class H>
odeint_system<H, Dim> make_odeint_system(H h, odeint_workspace<double, Dim>* workspace = nullptr) {
    return {std::move(h), workspace};
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
