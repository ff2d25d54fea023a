#pragma once
// A kinetic energy quadratic in p, T = p^T M^-1 p / 2, recognised once from
// the user's generic T, so that the velocity dT/dp = M^-1 p costs a product
// instead of a gradient at every step: a diagonal M^-1 for any size, a dense
// one up to dense_limit components. Hamilton's equations for such a T are
// Gould & Tobochnik's eq. 3.73b with v = p / m.
//
// Recognition is by measurement, to rounding: the gradient at two generic
// points must be the same linear map of p (diagonal first), vanish at p = 0,
// and satisfy p . dT/dp = 2 T (Euler's theorem for a function homogeneous of
// degree 2). A T that is not quadratic fails at least one of these at points
// chosen so that no component is zero or repeats; the steppers then go on
// differentiating T at every step, as before.
#include <algorithm>
#include <concepts>
#include <cmath>
#include <exception>
#include <limits>
#include <type_traits>

#include <Eigen/Core>

#include "hamiltonian.hpp"

namespace sympl {

template <class Vec>
class quadratic_kinetic {
public:
    using scalar = scalar_of<Vec>;
    using matrix = Eigen::Matrix<scalar, Eigen::Dynamic, Eigen::Dynamic>;
    // analytic: H gives its velocity, nothing to recognise; not_quadratic: dT/dp
    // stays a gradient of T at every call (also for scalars that are not plain
    // floating-point numbers).
    enum class form { unknown, analytic, diagonal, dense, not_quadratic };
    static constexpr Eigen::Index dense_limit = 32;

    // Measures T of `h` in dimension n. Only for a T with no analytic velocity
    // and a plain floating-point scalar. A T that throws at the probes is taken
    // as not quadratic: the steppers then meet the error where they evaluate it.
    template <class H>
    void recognise(const H& h, Eigen::Index n) {
        dimension_ = n;
        uniform_ = false;
        form_ = has_analytic_velocity<H, Vec> ? form::analytic : form::not_quadratic;
        if constexpr (!has_analytic_velocity<H, Vec> && std::is_floating_point_v<scalar>) {
            try {
                if (n > 0) form_ = measure(h, n);
            } catch (const std::exception&) {
                form_ = form::not_quadratic;
            }
        }
    }

    form recognised() const { return form_; }
    Eigen::Index dimension() const { return dimension_; }
    bool applies() const { return form_ == form::diagonal || form_ == form::dense; }

    // v = M^-1 p where T was recognised as quadratic (applies() is true).
    [[gnu::always_inline]] inline void velocity(const Vec& p, Vec& v) const {
        if (form_ == form::diagonal) {
            // Equal masses (every particle of a chain or a cluster): one stream, p, not two.
            if (uniform_) v.noalias() = diagonal_[0] * p;
            else v.noalias() = diagonal_.cwiseProduct(p);
        } else {
            v.noalias() = dense_ * p;
        }
    }
    // The inverse mass matrix found: its diagonal, or the whole matrix.
    const Vec& inverse_mass_diagonal() const { return diagonal_; }
    const matrix& inverse_mass() const { return dense_; }

private:
    template <class H>
    form measure(const H& h, Eigen::Index n) {
        const Vec p1 = probe(n, 0), p2 = probe(n, 1), zero = Vec::Zero(n);
        Vec v1, v2, v0;
        sympl::velocity(h, p1, v1);
        sympl::velocity(h, p2, v2);
        sympl::velocity(h, zero, v0);
        if (!homogeneous(h, p1, v1) || !homogeneous(h, p2, v2) || !close(v0, zero, v1)) return form::not_quadratic;
        diagonal_ = v1.cwiseQuotient(p1);
        if (close(diagonal_.cwiseProduct(p2), v2, v2)) {
            // Uniform only when c p reproduces both probes as the diagonal does.
            uniform_ = close(diagonal_[0] * p1, v1, v1) && close(diagonal_[0] * p2, v2, v2);
            return form::diagonal;
        }
        if (n > dense_limit) return form::not_quadratic;
        dense_.resize(n, n);
        Vec e = Vec::Zero(n), column;
        for (Eigen::Index j = 0; j < n; ++j) {
            e[j] = scalar(1);
            sympl::velocity(h, e, column);
            dense_.col(j) = column;
            e[j] = scalar(0);
        }
        const Vec predicted1 = dense_ * p1, predicted2 = dense_ * p2;
        const bool symmetric =
            (dense_ - dense_.transpose()).cwiseAbs().maxCoeff() <= tolerance() * dense_.cwiseAbs().maxCoeff();
        return close(predicted1, v1, v1) && close(predicted2, v2, v2) && symmetric ? form::dense : form::not_quadratic;
    }
    // No component zero, none equal, signs mixed: a generic point.
    static Vec probe(Eigen::Index n, int which) {
        Vec p = Vec::Zero(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            const scalar x = scalar(0.61803398874989485) * scalar(i + 1 + 7 * which);
            p[i] = (scalar(1) + x - std::floor(x)) * ((i + which) % 3 == 0 ? scalar(-1) : scalar(1));
        }
        return p;
    }
    static scalar tolerance() { return scalar(64) * Eigen::NumTraits<scalar>::epsilon(); }
    // |a - b| within rounding of the size of `scale`, in the max norm.
    static bool close(const Vec& a, const Vec& b, const Vec& scale) {
        const scalar s = std::max(scale.cwiseAbs().maxCoeff(), (std::numeric_limits<scalar>::min)());
        return (a - b).cwiseAbs().maxCoeff() <= tolerance() * s;
    }
    template <class H>
    static bool homogeneous(const H& h, const Vec& p, const Vec& v) {
        using std::abs;
        using std::isfinite;
        const scalar two_t = scalar(2) * scalar(h.kinetic(p)), pv = p.dot(v);
        return isfinite(two_t) && abs(two_t - pv) <= tolerance() * p.cwiseAbs().dot(v.cwiseAbs());
    }

    Vec diagonal_;
    bool uniform_ = false;  // the diagonal is one number (equal masses)
    matrix dense_;
    Eigen::Index dimension_ = -1;
    form form_ = form::unknown;
};

// dT/dp: p itself where the Hamiltonian says so at run time (a system behind
// function pointers, src/running/erased_system.hpp: one indirect call saved
// per stage), M^-1 p where `kinetic` finds T quadratic (measured here at the
// first call with a new dimension), else the Hamiltonian's own velocity or a
// gradient of its generic T. For the steppers that hold a quadratic_kinetic.
template <class H, class Vec>
[[gnu::always_inline]] inline void recognised_velocity(const H& h, quadratic_kinetic<Vec>& kinetic, const Vec& p,
                                                        Vec& v) {
    if constexpr (requires { { h.velocity_is_p() } -> std::same_as<bool>; }) {
        if (h.velocity_is_p()) {
            v = p;
            return;
        }
    }
    if constexpr (!has_analytic_velocity<H, Vec> && std::is_floating_point_v<scalar_of<Vec>>) {
        if (kinetic.dimension() != p.size()) kinetic.recognise(h, p.size());
        if (kinetic.applies()) {
            kinetic.velocity(p, v);
            return;
        }
    }
    sympl::velocity(h, p, v);
}

}  // namespace sympl
