#pragma once
// A point (q, p) of phase space. Dim is the number of degrees of freedom:
// fixed at compile time (stack storage, no heap) or Eigen::Dynamic.
#include <cmath>
#include <cstddef>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "error.hpp"

namespace sympl {

template <class Scalar = double, int Dim = Eigen::Dynamic>
struct phase_space {
    static_assert(Dim == Eigen::Dynamic || Dim >= 1, "a phase space needs at least one degree of freedom");
    using scalar = Scalar;
    using vector = Eigen::Matrix<Scalar, Dim, 1>;
    static constexpr int dimension = Dim;

    vector q;
    vector p;

    phase_space() : q(vector::Zero(Dim == Eigen::Dynamic ? 0 : Dim)), p(q) {}
    // n degrees of freedom, all zero.
    explicit phase_space(Eigen::Index n) : q(vector::Zero(n)), p(vector::Zero(n)) {
        if (Dim != Eigen::Dynamic && n != Dim)
            throw invalid_argument("phase_space: " + std::to_string(n) +
                                   " degrees of freedom requested for a state of fixed dimension " +
                                   std::to_string(Dim));
    }
    phase_space(vector q_, vector p_) : q(std::move(q_)), p(std::move(p_)) {
        if (q.size() != p.size())
            throw invalid_argument("phase_space: q has " + std::to_string(q.size()) + " components but p has " +
                                   std::to_string(p.size()) + "; expected equal dimensions");
    }
    // Build from any Eigen expressions (e.g. Eigen::Vector2d, a VectorXd of the same size).
    template <class DQ, class DP>
    phase_space(const Eigen::MatrixBase<DQ>& q_, const Eigen::MatrixBase<DP>& p_)
        : phase_space(vector(q_), vector(p_)) {}

    Eigen::Index size() const { return q.size(); }

    // The same state in another scalar type or storage (e.g. double -> long double, fixed -> dynamic).
    template <class S2, int D2 = Dim>
    phase_space<S2, D2> cast() const {
        return phase_space<S2, D2>(q.template cast<S2>(), p.template cast<S2>());
    }
};

template <class X>
concept phase_space_state = requires(X x) {
    typename X::scalar;
    typename X::vector;
    x.q;
    x.p;
};

// True when every component of q and p is finite.
template <class S, int D>
bool is_finite(const phase_space<S, D>& x) {
    using std::isfinite;
    for (Eigen::Index i = 0; i < x.size(); ++i)
        if (!isfinite(x.q[i]) || !isfinite(x.p[i])) return false;
    return true;
}

// Largest absolute difference between two states (max norm over q and p).
template <class S, int D>
S max_difference(const phase_space<S, D>& a, const phase_space<S, D>& b) {
    if (a.size() != b.size())
        throw invalid_argument("max_difference: states of dimension " + std::to_string(a.size()) + " and " +
                               std::to_string(b.size()) + "; expected equal dimensions");
    if (a.size() == 0) return S(0);
    return std::max((a.q - b.q).cwiseAbs().maxCoeff(), (a.p - b.p).cwiseAbs().maxCoeff());
}

namespace detail {
template <int Dim, class Container>
void check_stacked(const Container& x, const char* who) {
    const std::size_t n = std::size(x);
    if (n % 2 != 0 || (Dim != Eigen::Dynamic && n != std::size_t(2 * Dim)))
        throw invalid_argument(std::string(who) + ": a state of " + std::to_string(n) +
                               " numbers; expected q and p stacked" +
                               (Dim != Eigen::Dynamic ? ", " + std::to_string(2 * Dim) + " numbers" : std::string()));
}
}  // namespace detail

// (q, p) -> (q_1 .. q_n, p_1 .. p_n): the first-order form of Odeint and of
// the program's files.
template <class S, int D>
std::vector<S> stacked(const phase_space<S, D>& x) {
    std::vector<S> y(static_cast<std::size_t>(2 * x.size()));
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        y[i] = x.q[i];
        y[x.size() + i] = x.p[i];
    }
    return y;
}

// (q_1 .. q_n, p_1 .. p_n) -> (q, p), from any sized container of numbers.
template <class State, class Container>
State from_stacked(const Container& y) {
    detail::check_stacked<State::dimension>(y, "from_stacked");
    const auto n = static_cast<Eigen::Index>(std::size(y) / 2);
    State x(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        x.q[i] = typename State::scalar(y[i]);
        x.p[i] = typename State::scalar(y[n + i]);
    }
    return x;
}


}  // namespace sympl
