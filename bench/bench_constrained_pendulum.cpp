// Is the double pendulum faster as a constrained system? The built-in scene's
// double pendulum (unit masses and lengths, g = 1, from angles (1, 0.5) and
// canonical momenta (0.2, -0.1)) written as two point masses in the plane
// joined by rigid rods: H = |v1|^2/2 m1 + |v2|^2/2 m2 + g (m1 y1 + m2 y2)
// with |x1| = l1, |x2 - x1| = l2, where V is linear and the force constant.
// RATTLE (Andersen 1983, J. Comput. Phys. 52, 24; Hairer, Lubich & Wanner,
// Geometric Numerical Integration, sec. VII.1.4) is symplectic and symmetric
// on the constraint manifold, so its compositions (the catalog's composition
// weights, catalog_forms.hpp) are symplectic of the composition's order. It
// costs no sine, but each substep solves the two position constraints by
// Newton's method (started from the last substep's multipliers, ended at the
// rounding plateau) and projects the velocities.
// Over the scene's span t = 2000: each composition's max relative energy
// error (every step) and time (least of 3), beside Odeint's Bulirsch-Stoer on
// the canonical H through integrate_adaptive (absolute = relative tolerance,
// as the program runs it), in one process. docs/nonseparable.md quotes it.
//   bench_constrained_pendulum
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include <sympl/hamiltonians/double_pendulum.hpp>
#include <sympl/sympl.hpp>

namespace {

constexpr double m1 = 1, m2 = 1, l1 = 1, l2 = 1, g = 1, span = 2000;

// Positions, velocities and the last substep's multipliers (rod tensions).
struct rods {
    double x1, y1, x2, y2, u1, w1, u2, w2;
    double tension1 = 0, tension2 = 0;
    long newton_iterations = 0;
};

double energy(const rods& s) {  // the canonical H's zero: both masses hanging at rest
    return 0.5 * m1 * (s.u1 * s.u1 + s.w1 * s.w1) + 0.5 * m2 * (s.u2 * s.u2 + s.w2 * s.w2) +
           g * (m1 * s.y1 + m2 * s.y2) + (m1 + m2) * g * l1 + m2 * g * l2;
}

// One RATTLE step of h: x_new = x + h v + h^2/2 (a - M^-1 G(x)^T L) on the
// constraints (Newton on the 2 x 2 system for L), then v_new tangent to them.
void rattle(rods& s, double h) {
    const double c = h * h / 2, dx = s.x2 - s.x1, dy = s.y2 - s.y1;
    const double fx1 = s.x1 + h * s.u1, fy1 = s.y1 + h * s.w1 - c * g;  // unconstrained positions
    const double fx2 = s.x2 + h * s.u2, fy2 = s.y2 + h * s.w2 - c * g;
    double L1 = s.tension1, L2 = s.tension2, last = INFINITY;
    double X1, Y1, X2, Y2;
    const auto place = [&] {
        X1 = fx1 - c / m1 * (L1 * s.x1 - L2 * dx), Y1 = fy1 - c / m1 * (L1 * s.y1 - L2 * dy);
        X2 = fx2 - c / m2 * (L2 * dx), Y2 = fy2 - c / m2 * (L2 * dy);
    };
    for (int it = 0; it < 50; ++it) {
        place();
        const double DX = X2 - X1, DY = Y2 - Y1;
        const double g1 = (X1 * X1 + Y1 * Y1 - l1 * l1) / 2, g2 = (DX * DX + DY * DY - l2 * l2) / 2;
        const double J11 = -c / m1 * (X1 * s.x1 + Y1 * s.y1), J12 = c / m1 * (X1 * dx + Y1 * dy);
        const double J21 = c / m1 * (DX * s.x1 + DY * s.y1), J22 = -c * (1 / m1 + 1 / m2) * (DX * dx + DY * dy);
        const double det = J11 * J22 - J12 * J21;
        const double d1 = (g1 * J22 - g2 * J12) / det, d2 = (J11 * g2 - J21 * g1) / det;
        L1 -= d1, L2 -= d2, ++s.newton_iterations;
        const double size = std::fabs(d1) + std::fabs(d2);
        if (size == 0 || size >= last || size <= 4e-16 * (std::fabs(L1) + std::fabs(L2))) break;
        last = size;
    }
    place();
    const double k = h / 2;  // v + h/2 (a - M^-1 G(x)^T L), then the end's half kick of gravity
    const double a1 = s.u1 - k / m1 * (L1 * s.x1 - L2 * dx), b1 = s.w1 - k / m1 * (L1 * s.y1 - L2 * dy) - h * g;
    const double a2 = s.u2 - k / m2 * (L2 * dx), b2 = s.w2 - k / m2 * (L2 * dy) - h * g;
    const double DX = X2 - X1, DY = Y2 - Y1;  // G(x_new) v_new = 0: a 2 x 2 solve for the multipliers
    const double r1 = X1 * a1 + Y1 * b1, r2 = DX * (a2 - a1) + DY * (b2 - b1);
    const double A11 = (X1 * X1 + Y1 * Y1) / m1, A12 = -(X1 * DX + Y1 * DY) / m1;
    const double A22 = (DX * DX + DY * DY) * (1 / m1 + 1 / m2), det = A11 * A22 - A12 * A12;
    const double mu1 = (r1 * A22 - r2 * A12) / det, mu2 = (A11 * r2 - A12 * r1) / det;
    s.u1 = a1 - (mu1 * X1 - mu2 * DX) / m1, s.w1 = b1 - (mu1 * Y1 - mu2 * DY) / m1;
    s.u2 = a2 - mu2 * DX / m2, s.w2 = b2 - mu2 * DY / m2;
    s.x1 = X1, s.y1 = Y1, s.x2 = X2, s.y2 = Y2, s.tension1 = L1, s.tension2 = L2;
}

// The scene's start: angles from the downward vertical, velocities dH/dp.
rods start(const sympl::hamiltonians::double_pendulum& dp) {
    const Eigen::Vector2d q(1, 0.5), p(0.2, -0.1);
    Eigen::Vector2d w;
    dp.dH_dp(q, p, w);
    rods s{};
    s.x1 = l1 * std::sin(q[0]), s.y1 = -l1 * std::cos(q[0]);
    s.x2 = s.x1 + l2 * std::sin(q[1]), s.y2 = s.y1 - l2 * std::cos(q[1]);
    s.u1 = l1 * w[0] * std::cos(q[0]), s.w1 = l1 * w[0] * std::sin(q[0]);
    s.u2 = s.u1 + l2 * w[1] * std::cos(q[1]), s.w2 = s.w1 + l2 * w[1] * std::sin(q[1]);
    return s;
}

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

template <class Run>
double least_of_3(Run run) {
    double best = INFINITY;
    for (int r = 0; r < 3; ++r) {
        const double t0 = seconds();
        run();
        best = std::min(best, seconds() - t0);
    }
    return best;
}

void rattle_rows(const rods& s0, double e0) {
    for (const char* name : {"kahan_li_6", "kahan_li_8", "sofroniou_spaletta_10"}) {
        const auto gamma = sympl::detail::leapfrog_composition_weights(sympl::method(name), name).gamma;
        for (double dt : {0.4, 0.3, 0.2, 0.15, 0.1, 0.07, 0.05}) {
            const long n = std::lround(span / dt);
            rods s = s0;
            double worst = 0;
            for (long k = 0; k < n; ++k) {
                for (double w : gamma) rattle(s, w * dt);
                worst = std::max(worst, std::fabs(energy(s) / e0 - 1));
            }
            double sink = 0;
            const double time = least_of_3([&] {
                rods t = s0;
                for (long k = 0; k < n; ++k)
                    for (double w : gamma) rattle(t, w * dt);
                sink += t.x1;
            });
            std::printf("rattle(%s)%*s dt %-5g  max energy error %8.2e  %7.2f ms  Newton %.2f / substep%s\n", name,
                        int(22 - std::string(name).size()), "", dt, worst, time * 1e3,
                        double(s.newton_iterations) / double(n * long(gamma.size())), sink == 1 ? " " : "");
        }
    }
}

void odeint_rows(const sympl::hamiltonians::double_pendulum& dp, double e0) {
    namespace odeint = boost::numeric::odeint;
    using state = std::array<double, 4>;
    const auto rhs = [&](const state& y, state& dy, double) {
        const Eigen::Vector2d q(y[0], y[1]), p(y[2], y[3]);
        Eigen::Vector2d a, b;
        dp.dH_dp(q, p, a), dp.dH_dq(q, p, b);
        dy = {a[0], a[1], -b[0], -b[1]};
    };
    for (double tol : {1e-10, 1e-11, 1e-12, 1e-13, 1e-14}) {
        state y = {1, 0.5, 0.2, -0.1};
        double worst = 0;
        odeint::integrate_adaptive(odeint::bulirsch_stoer<state>(tol, tol), rhs, y, 0.0, span, 0.1,
                                   [&](const state& z, double) {
                                       const Eigen::Vector2d q(z[0], z[1]), p(z[2], z[3]);
                                       worst = std::max(worst, std::fabs(dp.energy(q, p) / e0 - 1));
                                   });
        const double time = least_of_3([&] {
            state z = {1, 0.5, 0.2, -0.1};
            odeint::integrate_adaptive(odeint::bulirsch_stoer<state>(tol, tol), rhs, z, 0.0, span, 0.1);
        });
        std::printf("odeint_bulirsch_stoer  tolerance %-6g  max energy error %8.2e  %7.2f ms\n", tol, worst, time * 1e3);
    }
}

}  // namespace

int main() {
    const sympl::hamiltonians::double_pendulum dp{};
    const rods s0 = start(dp);
    const double e0 = dp.energy(Eigen::Vector2d(1, 0.5), Eigen::Vector2d(0.2, -0.1));
    std::printf("Double pendulum over t = %g: H = %.17g (canonical), %.17g (rods)\n", span, e0, energy(s0));
    rattle_rows(s0, e0);
    odeint_rows(dp, e0);
}
