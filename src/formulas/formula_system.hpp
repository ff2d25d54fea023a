#pragma once
// A system written as formulas in a scene (issue 57): T(p) and V(q), or one
// H(q, p), read once (formula.hpp), compiled once per run into machine code
// with their gradients (formula_code.hpp, machine_code.hpp) for doubles and
// long doubles, and evaluated by the interpreter (formula_eval.hpp) on the
// other scalars the library asks for (the dual numbers of Gauss-Legendre's
// Newton Jacobian, of MEGNO's tangent and of force-gradient kicks), through
// which the library's automatic differentiation takes what else it needs.
// Without a compiler every scalar runs on the interpreter.
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include <sympl/core/hamiltonian.hpp>

#include "formulas/formula.hpp"
#include "formulas/formula_eval.hpp"
#include "formulas/machine_code.hpp"

namespace sympl::app::formulas {

template <class R>
using value_of_p = R (*)(const R*, const double*);
template <class R>
using gradient_of_x = void (*)(const R*, R*, const double*, long);
template <class R>
using value_of_qp = R (*)(const R*, const R*, const double*);
template <class R>
using gradient_of_qp = void (*)(const R*, const R*, R*, const double*, long);

// The compiled functions of one precision (null: interpreted).
template <class R>
struct compiled_functions {
    value_of_p<R> T = nullptr, V = nullptr;
    gradient_of_x<R> velocity = nullptr, force = nullptr;
    value_of_qp<R> H = nullptr;
    gradient_of_qp<R> dH_dq = nullptr, dH_dp = nullptr;
};

// What both kinds of formula system hold: the trees, the parameters' values
// (in the order of names::parameters), the degrees of freedom, and the code.
struct prepared_formulas {
    std::shared_ptr<const formula> T, V, H;  // T and V, or H
    std::vector<double> parameters;
    long dimension = 0;
    std::shared_ptr<const machine_code> code;  // null: interpreted
    std::string interpreted_because;           // why code is null
    bool velocity_is_p = false;                // T = sum p_i^2 / 2 (prepare() checks)
    compiled_functions<double> d;
    compiled_functions<long double> l;

    template <class R>
    const compiled_functions<R>& of() const {
        if constexpr (std::is_same_v<R, double>) return d;
        else return l;
    }
};

// Prepares T and V, or H (an empty T and V): compiles their code and checks
// every index of q and p and every sum's bound at x0 by the interpreter (no
// index depends on q or p, so what holds there holds at every state).
std::shared_ptr<const prepared_formulas> prepare(std::shared_ptr<const formula> T, std::shared_ptr<const formula> V,
                                                 std::shared_ptr<const formula> H, std::vector<double> parameters,
                                                 const std::vector<double>& x0);

template <class Vec>
inline constexpr bool compiled_scalar =
    std::is_same_v<scalar_of<Vec>, double> || std::is_same_v<scalar_of<Vec>, long double>;

namespace detail {
inline void check_size(Eigen::Index size, long dimension) {
    if (size != dimension)
        throw invalid_argument("formula system: a state of " + std::to_string(size) + " components; expected " +
                               std::to_string(dimension));
}
}  // namespace detail

// H = T(p) + V(q) from formulas.
class separable_formulas {
public:
    explicit separable_formulas(std::shared_ptr<const prepared_formulas> f) : f_(std::move(f)) {}

    long dimension() const { return f_->dimension; }

    template <class Vec>
    scalar_of<Vec> kinetic(const Vec& p) const {
        using S = scalar_of<Vec>;
        if constexpr (compiled_scalar<Vec>)
            if (f_->code) {
                detail::check_size(p.size(), f_->dimension);
                return f_->of<S>().T(p.data(), f_->parameters.data());
            }
        return evaluate<S>(*f_->T, f_->parameters, Vec(), p);
    }
    template <class Vec>
    scalar_of<Vec> potential(const Vec& q) const {
        using S = scalar_of<Vec>;
        if constexpr (compiled_scalar<Vec>)
            if (f_->code) {
                detail::check_size(q.size(), f_->dimension);
                return f_->of<S>().V(q.data(), f_->parameters.data());
            }
        return evaluate<S>(*f_->V, f_->parameters, q, Vec());
    }
    // f = -dV/dq and v = dT/dp for doubles and long doubles: compiled, or
    // the library's reverse mode on the interpreter; any other scalar takes
    // the library's own differentiation of kinetic() and potential().
    template <class Vec>
        requires compiled_scalar<Vec>
    void force(const Vec& q, Vec& f) const {
        using S = scalar_of<Vec>;
        detail::check_size(q.size(), f_->dimension);
        if (f.size() != q.size()) f.resize(q.size());
        if (f_->code) f_->of<S>().force(q.data(), f.data(), f_->parameters.data(), f_->dimension);
        else sympl::detail::gradient([&](const auto& x) { return this->potential(x); }, q, f, S(-1));
    }
    template <class Vec>
        requires compiled_scalar<Vec>
    void velocity(const Vec& p, Vec& v) const {
        using S = scalar_of<Vec>;
        detail::check_size(p.size(), f_->dimension);
        if (v.size() != p.size()) v.resize(p.size());
        if (f_->code) f_->of<S>().velocity(p.data(), v.data(), f_->parameters.data(), f_->dimension);
        else sympl::detail::gradient([&](const auto& x) { return this->kinetic(x); }, p, v);
    }

    const prepared_formulas& prepared() const { return *f_; }
    // dT/dp = p: drifts need no call (core/splitting_loop.hpp).
    bool velocity_is_p() const { return f_->velocity_is_p; }

private:
    std::shared_ptr<const prepared_formulas> f_;
};

// Any H(q, p) from one formula.
class general_formulas {
public:
    explicit general_formulas(std::shared_ptr<const prepared_formulas> f) : f_(std::move(f)) {}

    long dimension() const { return f_->dimension; }

    template <class Vec>
    scalar_of<Vec> energy(const Vec& q, const Vec& p) const {
        using S = scalar_of<Vec>;
        if constexpr (compiled_scalar<Vec>)
            if (f_->code) {
                detail::check_size(q.size(), f_->dimension);
                detail::check_size(p.size(), f_->dimension);
                return f_->of<S>().H(q.data(), p.data(), f_->parameters.data());
            }
        return evaluate<S>(*f_->H, f_->parameters, q, p);
    }
    template <class Vec>
        requires compiled_scalar<Vec>
    void dH_dq(const Vec& q, const Vec& p, Vec& out) const {
        gradient(q, p, out, true);
    }
    template <class Vec>
        requires compiled_scalar<Vec>
    void dH_dp(const Vec& q, const Vec& p, Vec& out) const {
        gradient(q, p, out, false);
    }

    const prepared_formulas& prepared() const { return *f_; }

private:
    template <class Vec>
    void gradient(const Vec& q, const Vec& p, Vec& out, bool by_q) const {
        using S = scalar_of<Vec>;
        detail::check_size(q.size(), f_->dimension);
        detail::check_size(p.size(), f_->dimension);
        if (out.size() != q.size()) out.resize(q.size());
        if (f_->code) {
            const auto& c = f_->of<S>();
            (by_q ? c.dH_dq : c.dH_dp)(q.data(), p.data(), out.data(), f_->parameters.data(), f_->dimension);
        } else if (by_q) {
            sympl::detail::gradient(
                [&](const auto& x) {
                    using X = std::decay_t<decltype(x)>;
                    return energy(x, X(p.template cast<scalar_of<X>>()));
                },
                q, out);
        } else {
            sympl::detail::gradient(
                [&](const auto& x) {
                    using X = std::decay_t<decltype(x)>;
                    return energy(X(q.template cast<scalar_of<X>>()), x);
                },
                p, out);
        }
    }

    std::shared_ptr<const prepared_formulas> f_;
};

}  // namespace sympl::app::formulas
