#pragma once
// A system of any type behind a few function pointers: what the generic path
// (generic_path.hpp) runs on where a system's registry entry compiles nothing
// of its own. Each of T, V, force and velocity (or H, dH/dq and dH/dp) is one
// indirect call on dynamic-size vectors of a few scalar types: double for the
// runs, long double for the references, the dual numbers of Gauss-Legendre's
// Newton Jacobian and of MEGNO's tangent. The kinds' templates are then
// compiled once for these two types instead of once per system (docs/layout.md,
// "What the program compiles"). The concrete side of each pointer is
// instantiated in the system's own translation unit (of()); a scalar its
// system cannot take throws where it is called.
#include <concepts>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

#include <sympl/core/dual.hpp>
#include <sympl/core/general_hamiltonian.hpp>
#include <sympl/core/hamiltonian.hpp>

namespace sympl::app {

template <class S>
using erased_vector_of = Eigen::Matrix<S, Eigen::Dynamic, 1>;
using erased_vector = erased_vector_of<double>;

namespace detail {

// The calls of one scalar type S on a separable system: T, V, force, velocity.
template <class S>
struct separable_calls {
    using V = erased_vector_of<S>;
    S (*kinetic)(const void*, const V&) = nullptr;
    S (*potential)(const void*, const V&) = nullptr;
    void (*force)(const void*, const V&, V&) = nullptr;
    void (*velocity)(const void*, const V&, V&) = nullptr;

    template <class Sys>
    static separable_calls of() {
        separable_calls c;
        if constexpr (separable_hamiltonian<Sys, V>) {
            c.kinetic = [](const void* s, const V& p) { return S(static_cast<const Sys*>(s)->kinetic(p)); };
            c.potential = [](const void* s, const V& q) { return S(static_cast<const Sys*>(s)->potential(q)); };
            c.force = [](const void* s, const V& q, V& f) { sympl::force(*static_cast<const Sys*>(s), q, f); };
            c.velocity = [](const void* s, const V& p, V& v) { sympl::velocity(*static_cast<const Sys*>(s), p, v); };
        } else {
            c.kinetic = c.potential = [](const void*, const V&) -> S { refuse_scalar(); };
            c.force = c.velocity = [](const void*, const V&, V&) { refuse_scalar(); };
        }
        return c;
    }
    [[noreturn]] static void refuse_scalar() {
        throw invalid_argument("the system's T and V are not written for this scalar type (dual numbers or long "
                               "double); expected T and V templated on the vector type");
    }
};

// The calls of one scalar type S on any H(q, p): H, dH/dq, dH/dp.
template <class S>
struct general_calls {
    using V = erased_vector_of<S>;
    S (*energy)(const void*, const V&, const V&) = nullptr;
    void (*dH_dq)(const void*, const V&, const V&, V&) = nullptr;
    void (*dH_dp)(const void*, const V&, const V&, V&) = nullptr;

    template <class H>
    static general_calls of() {
        general_calls c;
        if constexpr (general_hamiltonian<H, V>) {
            c.energy = [](const void* s, const V& q, const V& p) { return S(static_cast<const H*>(s)->energy(q, p)); };
            c.dH_dq = [](const void* s, const V& q, const V& p, V& out) {
                sympl::dH_dq(*static_cast<const H*>(s), q, p, out);
            };
            c.dH_dp = [](const void* s, const V& q, const V& p, V& out) {
                sympl::dH_dp(*static_cast<const H*>(s), q, p, out);
            };
        } else {
            c.energy = [](const void*, const V&, const V&) -> S { separable_calls<S>::refuse_scalar(); };
            c.dH_dq = c.dH_dp = [](const void*, const V&, const V&, V&) { separable_calls<S>::refuse_scalar(); };
        }
        return c;
    }
};

template <class S, class... Ts>
inline constexpr bool one_of = (std::same_as<S, Ts> || ...);

}  // namespace detail

// H = T(p) + V(q) of a separable system, type-erased: on doubles (the runs),
// long doubles (the reference), dual<double, 8> (a separable system taken as a
// general one in Gauss-Legendre's Newton Jacobian) and dual<double, 1>
// (MEGNO's tangent in ensembles).
class erased_separable {
public:
    template <class S>
    static constexpr bool takes = detail::one_of<S, double, long double, dual<double, 8>, dual<double, 1>>;

    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    scalar_of<V> kinetic(const V& p) const {
        return calls<scalar_of<V>>().kinetic(self_.get(), p);
    }
    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    scalar_of<V> potential(const V& q) const {
        return calls<scalar_of<V>>().potential(self_.get(), q);
    }
    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    void force(const V& q, V& f) const {
        calls<scalar_of<V>>().force(self_.get(), q, f);
    }
    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    void velocity(const V& p, V& v) const {
        calls<scalar_of<V>>().velocity(self_.get(), p, v);
    }
    // dT/dp is p itself (unit masses), so that a drift needs no call: the
    // splitting loop's velocity_is_p (core/splitting_loop.hpp).
    bool velocity_is_p() const { return velocity_is_p_; }
    // J_F(q) u for the force-gradient kicks, on doubles; a system without it
    // was refused before the run by its form (requirements.hpp).
    void force_derivative(const erased_vector& q, const erased_vector& u, erased_vector& df) const {
        force_derivative_(self_.get(), q, u, df);
    }

    template <class Sys>
    static erased_separable of(Sys sys) {
        erased_separable e;
        e.self_ = std::make_shared<const Sys>(std::move(sys));
        e.calls_ = {detail::separable_calls<double>::of<Sys>(), detail::separable_calls<long double>::of<Sys>(),
                    detail::separable_calls<dual<double, 8>>::of<Sys>(),
                    detail::separable_calls<dual<double, 1>>::of<Sys>()};
        e.velocity_is_p_ = velocity_is_identity(*static_cast<const Sys*>(e.self_.get()));
        e.force_derivative_ = [](const void* s, const erased_vector& q, const erased_vector& u, erased_vector& df) {
            if constexpr (differentiable_force<Sys, erased_vector>)
                sympl::force_derivative(*static_cast<const Sys*>(s), q, u, df);
            else
                throw invalid_argument("the system gives neither force_derivative nor a potential templated on its "
                                       "scalar");
        };
        return e;
    }

private:
    template <class S>
    const detail::separable_calls<S>& calls() const {
        return std::get<detail::separable_calls<S>>(calls_);
    }

    // A system's velocity(p) that hands back p itself, as a compiled run
    // would find it; or a system that says so (a formula system whose T is
    // sum p_i^2 / 2).
    template <class Sys>
    static bool velocity_is_identity(const Sys& sys) {
        if constexpr (requires { { sys.velocity_is_p() } -> std::same_as<bool>; }) {
            return sys.velocity_is_p();
        } else if constexpr (requires(const erased_vector& p) {
                                 { sys.velocity(p) } -> std::same_as<const erased_vector&>;
                             }) {
            const erased_vector p = erased_vector::Ones(1);
            return &sys.velocity(p) == &p;
        } else {
            return false;
        }
    }

    std::shared_ptr<const void> self_;
    std::tuple<detail::separable_calls<double>, detail::separable_calls<long double>,
               detail::separable_calls<dual<double, 8>>, detail::separable_calls<dual<double, 1>>>
        calls_;
    bool velocity_is_p_ = false;
    void (*force_derivative_)(const void*, const erased_vector&, const erased_vector&, erased_vector&) = nullptr;
};

// An erased separable system on fixed-size states of N degrees of freedom:
// the generic path's RKN pairs on a state of one number (generic_path.cpp),
// whose stage sums on dynamic-size vectors cost about twice the compiled
// pairs' (docs/speed.md, "The generic path"). A call on a fixed-size vector
// copies its N numbers into the dynamic vector the erased call takes and the
// result back; a call on dynamic vectors is the erased system's own (the
// program's form and energy read those).
template <int N>
class erased_fixed_size {
public:
    using fixed = Eigen::Matrix<double, N, 1>;
    explicit erased_fixed_size(erased_separable sys) : sys_(std::move(sys)) {}

    template <class V>
        requires erased_separable::takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    scalar_of<V> kinetic(const V& p) const {
        return sys_.kinetic(p);
    }
    template <class V>
        requires erased_separable::takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    scalar_of<V> potential(const V& q) const {
        return sys_.potential(q);
    }
    template <class V>
        requires erased_separable::takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    void force(const V& q, V& f) const {
        sys_.force(q, f);
    }
    template <class V>
        requires erased_separable::takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    void velocity(const V& p, V& v) const {
        sys_.velocity(p, v);
    }

    double kinetic(const fixed& p) const {
        double t = 0;
        with_copies(p, [&](const erased_vector& in, erased_vector&) { t = sys_.kinetic(in); });
        return t;
    }
    double potential(const fixed& q) const {
        double v = 0;
        with_copies(q, [&](const erased_vector& in, erased_vector&) { v = sys_.potential(in); });
        return v;
    }
    void force(const fixed& q, fixed& f) const {
        with_copies(q, [&](const erased_vector& in, erased_vector& out) {
            sys_.force(in, out);
            copy_out(out, f);
        });
    }
    void velocity(const fixed& p, fixed& v) const {
        with_copies(p, [&](const erased_vector& in, erased_vector& out) {
            sys_.velocity(in, out);
            copy_out(out, v);
        });
    }
    bool velocity_is_p() const { return sys_.velocity_is_p(); }

private:
    // The call on x copied into this thread's dynamic vectors. A call made
    // inside another (a Python force that runs sympl) gets vectors of its
    // own, so the outer call's input stays put.
    template <class Call>
    static void with_copies(const fixed& x, Call&& call) {
        struct scratch {
            erased_vector in = erased_vector(N), out = erased_vector(N);
            bool busy = false;
        };
        thread_local scratch s;
        if (s.busy) {
            erased_vector in = x, out(N);
            return call(std::as_const(in), out);
        }
        struct release {
            bool& busy;
            ~release() { busy = false; }
        };
        s.busy = true;
        const release guard{s.busy};
        s.in = x;
        s.out.resize(N);  // as the last call left it, which may have been refused for its size
        call(std::as_const(s.in), s.out);
    }
    // A force or velocity of N numbers into y; any other size refused (a
    // system that writes another would be read past).
    static void copy_out(const erased_vector& out, fixed& y) {
        if (out.size() != N)
            throw invalid_argument("the system's force or velocity gave " + std::to_string(out.size()) +
                                   " numbers for a state of " + std::to_string(N) + " degrees of freedom");
        y = out;
    }

    erased_separable sys_;
};

// Any H(q, p), type-erased: on doubles, long doubles (the reference) and the
// dual numbers of Gauss-Legendre's Newton Jacobian in both.
class erased_general {
public:
    template <class S>
    static constexpr bool takes = detail::one_of<S, double, long double, dual<double, 8>, dual<long double, 8>>;

    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    scalar_of<V> energy(const V& q, const V& p) const {
        return calls<scalar_of<V>>().energy(self_.get(), q, p);
    }
    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    void dH_dq(const V& q, const V& p, V& out) const {
        calls<scalar_of<V>>().dH_dq(self_.get(), q, p, out);
    }
    template <class V>
        requires takes<scalar_of<V>> && std::same_as<V, erased_vector_of<scalar_of<V>>>
    void dH_dp(const V& q, const V& p, V& out) const {
        calls<scalar_of<V>>().dH_dp(self_.get(), q, p, out);
    }

    template <class H>
    static erased_general of(H h) {
        erased_general e;
        e.self_ = std::make_shared<const H>(std::move(h));
        e.calls_ = {detail::general_calls<double>::of<H>(), detail::general_calls<long double>::of<H>(),
                    detail::general_calls<dual<double, 8>>::of<H>(),
                    detail::general_calls<dual<long double, 8>>::of<H>()};
        return e;
    }

private:
    template <class S>
    const detail::general_calls<S>& calls() const {
        return std::get<detail::general_calls<S>>(calls_);
    }

    std::shared_ptr<const void> self_;
    std::tuple<detail::general_calls<double>, detail::general_calls<long double>,
               detail::general_calls<dual<double, 8>>,
               detail::general_calls<dual<long double, 8>>>
        calls_;
};

}  // namespace sympl::app
