#pragma once
// Extrapolation of a symmetric one-step method to zero step size (Gragg 1965;
// Bulirsch & Stoer 1966; Hairer, Norsett & Wanner, Solving ODEs I, ch. II.9):
// one macro step of size H runs the inner method with n_j = j sub-steps of
// H/n_j (j = 1..k) and reads the polynomial in h^2 through the k results at
// h = 0; each column removes the next even power of the error, order
// p + 2(k - 1) at k(k+1)/2 inner steps. With the LogH leapfrog
// (time_transformation.hpp) this is the scheme of Mikkola & Tanikawa 1999
// (MNRAS 310, 745) and Preto & Tremaine 1999 (AJ 118, 2532). Not symplectic.
// Why the sequence 1, 2, 3, ... and the weights: docs/eccentric-orbits.md.
//
//   sympl::splitting_stepper<sympl::logh<Kepler>, X> leapfrog({kepler}, sympl::method("leapfrog_dkd"));
//   sympl::extrapolation_stepper s(leapfrog, 6);   // order 12, 21 leapfrog steps per macro step
//   sympl::integrate_to_time(s, X, t_end, 0.8);
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"

namespace sympl {

// The order p of a table to be extrapolated, checked: extrapolation in powers
// of h^2 needs a symmetric table and its even claimed order.
inline int extrapolation_order(const table& t) {
    if (!t.is_symmetric())
        throw invalid_argument("table '" + t.name() +
                               "' is not symmetric; extrapolation in powers of h^2 needs a symmetric method");
    if (t.order() < 2 || t.order() % 2 != 0)
        throw invalid_argument("table '" + t.name() + "' claims order " + std::to_string(t.order()) +
                               "; extrapolation needs its even order (>= 2)");
    return t.order();
}

// What extrapolation needs of the inner method: n steps of one size from a state.
template <class S>
concept multi_step_stepper = requires(S s, typename S::state_type& x, typename S::scalar dt, std::size_t n) {
    s.steps(x, dt, n);
};

template <multi_step_stepper Stepper>
class extrapolation_stepper {
public:
    using state_type = typename Stepper::state_type;
    using scalar = typename Stepper::scalar;

    static constexpr int max_columns = 16;

    // inner_order: the order p of the inner method; 0 takes the claimed order
    // of its table (inner.method().order()).
    extrapolation_stepper(Stepper inner, int columns, int inner_order = 0)
        : inner_(std::move(inner)), columns_(columns), inner_order_(inner_order) {
        if (columns < 1 || columns > max_columns)
            throw invalid_argument("extrapolation_stepper: columns = " + std::to_string(columns) + "; expected 1 to " +
                                   std::to_string(max_columns));
        if constexpr (requires { inner_.method().is_symmetric(); }) {
            try {
                const int claimed = extrapolation_order(inner_.method());
                if (inner_order_ == 0) inner_order_ = claimed;
            } catch (const invalid_argument& e) {
                throw invalid_argument(std::string("extrapolation_stepper: ") + e.what());
            }
        }
        if (inner_order_ < 2 || inner_order_ % 2 != 0)
            throw invalid_argument("extrapolation_stepper: inner order " + std::to_string(inner_order_) +
                                   "; expected the even order (>= 2) of the symmetric inner method");
        weights_ = weights(columns, inner_order_);
        for (scalar c : weights_) amplification_ += std::fabs(static_cast<double>(c));
    }

    // One macro step of size H.
    void step(state_type& x, scalar H) {
        for (int j = 1; j <= columns_; ++j) {
            trial_ = x;
            inner_.steps(trial_, H / scalar(j), static_cast<std::size_t>(j));
            // Combined as increments (sum c_j = 1): their rounding is relative to
            // the step's change, not to the state.
            const scalar c = weights_[static_cast<std::size_t>(j - 1)];
            if (j == 1) {
                sum_.q = c * (trial_.q - x.q);
                sum_.p = c * (trial_.p - x.p);
            } else {
                sum_.q += c * (trial_.q - x.q);
                sum_.p += c * (trial_.p - x.p);
            }
        }
        x.q += sum_.q;
        x.p += sum_.p;
    }
    void steps(state_type& x, scalar H, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) step(x, H);
    }
    // Each macro step starts afresh from its state: nothing carries over.
    void resume_steps(state_type& x, scalar H, std::size_t n) { steps(x, H, n); }

    int columns() const { return columns_; }
    int order() const { return inner_order_ + 2 * (columns_ - 1); }
    // Sum of |c_j|: how much the combination can magnify the rounding of the
    // inner results (1 for one column; 5/3 for two, Richardson's (4 T(h/2) - T(h))/3).
    double amplification() const { return amplification_; }
    // Inner steps per macro step.
    std::size_t inner_steps_per_step() const { return static_cast<std::size_t>(columns_ * (columns_ + 1) / 2); }
    const std::vector<scalar>& combination() const { return weights_; }

    std::uint64_t force_evaluations() const { return inner_.force_evaluations(); }
    std::uint64_t velocity_evaluations() const { return inner_.velocity_evaluations(); }
    void reset_counters() { inner_.reset_counters(); }
    const Stepper& inner() const { return inner_; }

private:
    // The result of n sub-steps is y + e_p (H/n)^p + e_{p+2} (H/n)^{p+2} + ...
    // (even powers from p on, for a symmetric method of order p). The weights
    // c_j of the runs with n_j = j keep y and cancel the first k - 1 error
    // terms: sum_j c_j = 1 and sum_j c_j j^-(p + 2i) = 0 for i = 0..k-2.
    // (For p = 2 this is the polynomial in h^2 read at h = 0.) Solved in long
    // double by Gaussian elimination with partial pivoting.
    static std::vector<scalar> weights(int k, int p) {
        std::vector<std::vector<long double>> a(static_cast<std::size_t>(k), std::vector<long double>(k + 1, 0.0L));
        for (int j = 0; j < k; ++j) a[0][j] = 1;
        a[0][k] = 1;
        for (int i = 1; i < k; ++i)
            for (int j = 0; j < k; ++j) a[i][j] = std::pow(1.0L / (j + 1), static_cast<long double>(p + 2 * (i - 1)));
        for (int c = 0; c < k; ++c) {
            int pivot = c;
            for (int r = c + 1; r < k; ++r)
                if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
            std::swap(a[c], a[pivot]);
            for (int r = 0; r < k; ++r) {
                if (r == c) continue;
                const long double f = a[r][c] / a[c][c];
                for (int j = c; j <= k; ++j) a[r][j] -= f * a[c][j];
            }
        }
        std::vector<scalar> c(static_cast<std::size_t>(k));
        for (int j = 0; j < k; ++j) c[j] = static_cast<scalar>(a[j][k] / a[j][j]);
        return c;
    }

    Stepper inner_;
    int columns_, inner_order_;
    std::vector<scalar> weights_;
    double amplification_ = 0;
    state_type trial_, sum_;
};

}  // namespace sympl
