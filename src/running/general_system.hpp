#pragma once
// A general Hamiltonian H(q, p) as the program runs it (runnable.hpp wraps every
// system that is a general_hamiltonian and not a separable one). To the
// methods for any H (Gauss-Legendre, Tao, semiexplicit) it is H itself; to the
// classic and Odeint steppers, which the library builds from a separable H or
// from equations of motion only, it is Hamilton's equations
//     dq/dt = dH/dp(q, p),   dp/dt = -dH/dq(q, p)
// (Gould & Tobochnik eq. 3.73 without the separation), with H's analytic
// gradients where it has them and dual numbers otherwise.
#include <sympl/core/general_hamiltonian.hpp>

namespace sympl::app {

template <class H>
struct general_system {
    H h;

    template <class V>
        requires general_hamiltonian<H, V>
    auto energy(const V& q, const V& p) const {
        return h.energy(q, p);
    }
    template <class V>
    void dH_dq(const V& q, const V& p, V& out) const {
        sympl::dH_dq(h, q, p, out);
    }
    template <class V>
    void dH_dp(const V& q, const V& p, V& out) const {
        sympl::dH_dp(h, q, p, out);
    }

    // A charged particle's particle and field, where H gives them (run_charged.hpp).
    auto particle() const
        requires requires(const H& x) { x.particle(); }
    {
        return h.particle();
    }
    auto electromagnetic_field() const
        requires requires(const H& x) { x.electromagnetic_field(); }
    {
        return h.electromagnetic_field();
    }

    // The equations of motion (equations_of_motion.hpp); dp/dt depends on p.
    template <class V, class T>
    void dq_dt(const V& q, const V& p, T, V& out) const {
        sympl::dH_dp(h, q, p, out);
    }
    template <class V, class T>
    void dp_dt(const V& q, const V& p, T, V& out) const {
        sympl::dH_dq(h, q, p, out);
        out = -out;
    }
};

}  // namespace sympl::app
