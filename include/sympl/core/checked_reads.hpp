#pragma once
// A Hamiltonian given as generic code (templated kinetic/potential, a general
// energy(q, p), the lambdas of make_hamiltonian) is evaluated once on vectors
// that check their element and block reads, before a stepper first runs it on a state
// of a new dimension. A V(q) that reads q[1] of a one-dimensional state would
// otherwise read memory it does not own in every force of a Release build
// (Eigen checks indices with eigen_assert only, which NDEBUG removes).
//
// The checked vector derives from the state's own Eigen vector, so whatever
// compiles for the state compiles for it and whole-vector operations
// (squaredNorm, dot, sum, arithmetic) run unchanged; only the element
// reads q[i], q(i), q.coeff(i), q.coeffRef(i), q.x() .. q.w() and the blocks
// q.segment, q.head, q.tail are checked. Reads through q.data(),
// q.array()[i] or q.block(...) are not seen.
//
// Cost: one evaluation of T and V (or H) per Hamiltonian type, state type,
// dimension and thread, at a stepper's first call; nothing per step. A Hamiltonian
// whose functions take only concrete vector types is still evaluated (on the
// vector, unchecked) and one whose functions refuse the checked type in their
// signature is left alone.
#include <string>

#include <Eigen/Core>

#include "error.hpp"

namespace sympl {

namespace detail {

// Which evaluation a checked vector belongs to, for the message.
struct read_site {
    const char* who;       // the stepper, e.g. "splitting_stepper"
    const char* function;  // "V(q)", "T(p)", "H(q, p)"
    const char* argument;  // "q" or "p"
};

template <class S, int Dim>
class checked_vector : public Eigen::Matrix<S, Dim, 1> {
public:
    using base = Eigen::Matrix<S, Dim, 1>;
    using Index = Eigen::Index;

    checked_vector(const base& v, const read_site& site) : base(v), site_(&site) {}
    // As any Eigen vector, for user code that builds one of its argument's type.
    using base::base;
    checked_vector() = default;
    template <class Other>
    checked_vector(const Eigen::MatrixBase<Other>& other) : base(other) {}
    using base::operator=;

    using base::operator();
    using base::coeff;
    using base::coeffRef;

    const S& operator[](Index i) const { return base::operator[](checked(i)); }
    S& operator[](Index i) { return base::operator[](checked(i)); }
    const S& operator()(Index i) const { return base::operator()(checked(i)); }
    S& operator()(Index i) { return base::operator()(checked(i)); }
    const S& coeff(Index i) const { return base::coeff(checked(i)); }
    const S& coeffRef(Index i) const { return base::coeffRef(checked(i)); }
    S& coeffRef(Index i) { return base::coeffRef(checked(i)); }
    const S& x() const { return (*this)[0]; }
    const S& y() const { return (*this)[1]; }
    const S& z() const { return (*this)[2]; }
    const S& w() const { return (*this)[3]; }
    S& x() { return (*this)[0]; }
    S& y() { return (*this)[1]; }
    S& z() { return (*this)[2]; }
    S& w() { return (*this)[3]; }

    // Blocks, as Eigen declares them (a run-time or a fixed length), their
    // range checked: N-body code reads a body as q.segment<3>(3 * i).
    template <class NType> auto segment(Index start, NType n) const {
        return base::segment(checked(start, length(n)), n);
    }
    template <class NType> auto segment(Index start, NType n) {
        return base::segment(checked(start, length(n)), n);
    }
    template <int N> auto segment(Index start, Index n = N) const {
        return base::template segment<N>(checked(start, n), n);
    }
    template <int N> auto segment(Index start, Index n = N) {
        return base::template segment<N>(checked(start, n), n);
    }
    template <class NType> auto head(NType n) const {
        checked(0, length(n));
        return base::head(n);
    }
    template <class NType> auto head(NType n) {
        checked(0, length(n));
        return base::head(n);
    }
    template <int N> auto head(Index n = N) const {
        checked(0, n);
        return base::template head<N>(n);
    }
    template <int N> auto head(Index n = N) {
        checked(0, n);
        return base::template head<N>(n);
    }
    template <class NType> auto tail(NType n) const {
        checked(this->size() - length(n), length(n));
        return base::tail(n);
    }
    template <class NType> auto tail(NType n) {
        checked(this->size() - length(n), length(n));
        return base::tail(n);
    }
    template <int N> auto tail(Index n = N) const {
        checked(this->size() - n, n);
        return base::template tail<N>(n);
    }
    template <int N> auto tail(Index n = N) {
        checked(this->size() - n, n);
        return base::template tail<N>(n);
    }

private:
    template <class NType> static Index length(NType n) { return Eigen::internal::get_runtime_value(n); }

    // i itself when components i .. i + count - 1 exist; otherwise the refusal.
    Index checked(Index i, Index count = 1) const {
        const Index n = this->size();
        if (i >= 0 && count >= 0 && i <= n - count) return i;
        const std::string last = count == 1 ? "" : ".." + std::to_string(i + count - 1);
        const std::string read = "[" + std::to_string(i) + last + "]";
        const std::string expected = n > 0 ? "expected indices 0.." + std::to_string(n - 1)
                                           : std::string("expected no read of an empty state");
        if (!site_)  // a vector the user's code built from q or p
            throw invalid_argument("the Hamiltonian read " + read + " of a vector of dimension " + std::to_string(n) +
                                   "; " + expected);
        throw invalid_argument(std::string(site_->who) + ": the Hamiltonian's " + site_->function + " read " +
                               site_->argument + read + " of a state of dimension " + std::to_string(n) + "; " +
                               expected);
    }

    const read_site* site_ = nullptr;
};

}  // namespace detail

// Evaluates h once on checked copies of x's q and p (see the top of this
// file); throws invalid_argument naming the index read and the dimension.
// Each function is tried only where its signature accepts the checked vector.
template <class H, class State>
void check_reads(const H& h, const State& x, const char* who) {
    using checked = detail::checked_vector<typename State::scalar, State::vector::RowsAtCompileTime>;
    const detail::read_site at_q{who, "V(q)", "q"}, at_p{who, "T(p)", "p"}, at_qp_q{who, "H(q, p)", "q"},
        at_qp_p{who, "H(q, p)", "p"};
    if constexpr (requires(const checked& v) { h.potential(v); }) (void)h.potential(checked(x.q, at_q));
    if constexpr (requires(const checked& v) { h.kinetic(v); }) (void)h.kinetic(checked(x.p, at_p));
    if constexpr (requires(const checked& q, const checked& p) { h.energy(q, p); })
        (void)h.energy(checked(x.q, at_qp_q), checked(x.p, at_qp_p));
}

// check_reads once per Hamiltonian type, state type, dimension and thread:
// what a stepper calls on every entry (one comparison when already checked).
template <class H, class State>
void check_reads_once(const H& h, const State& x, const char* who) {
    thread_local Eigen::Index checked_dimension = -1;
    if (x.q.size() == checked_dimension) return;
    check_reads(h, x, who);
    checked_dimension = x.q.size();  // only once it passed: a refused state is refused again
}

}  // namespace sympl
