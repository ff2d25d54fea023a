// What each way of writing H costs: nanoseconds per particle per leapfrog step
// (splitting_stepper::steps), side by side in one process, for
//   hand      force(q, f) and velocity(p, v) written by hand;
//   force     force(q, f) by hand, T = |p|^2/2 as a generic member (dT/dp by
//             automatic differentiation);
//   lambdas   T and V as two generic lambdas (make_hamiltonian), as README's
//             first program writes them: both gradients by automatic differentiation;
// on an FPU-beta chain (V a sum of near-neighbour terms, n = 1e2 .. 1e6) and a
// cluster of point masses (pairwise V, n = 1e2 .. 1e3 bodies in 3-D).
// Ratios are to `hand` in the same round; rounds interleave the contenders and
// the median is printed (the machines are shared and noisy).
//   bench_gradients [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>

namespace {

using State = sympl::phase_space<double>;

// V of a cluster of unit masses, G = 1, softened by eps^2 = 1e-2: q = (x1, y1, z1, x2, ...).
struct cluster_potential {
    template <class V> auto operator()(const V& q) const {
        using S = typename V::Scalar;
        using std::sqrt;
        const Eigen::Index bodies = q.size() / 3;
        S v(0);
        for (Eigen::Index i = 0; i < bodies; ++i)
            for (Eigen::Index j = i + 1; j < bodies; ++j) {
                const S dx = q[3 * i] - q[3 * j], dy = q[3 * i + 1] - q[3 * j + 1], dz = q[3 * i + 2] - q[3 * j + 2];
                v -= 1.0 / sqrt(dx * dx + dy * dy + dz * dz + 1e-2);
            }
        return v;
    }
};
struct cluster_force {
    void operator()(const Eigen::VectorXd& q, Eigen::VectorXd& f) const {
        const Eigen::Index bodies = q.size() / 3;
        f.setZero(q.size());
        for (Eigen::Index i = 0; i < bodies; ++i)
            for (Eigen::Index j = i + 1; j < bodies; ++j) {
                const double dx = q[3 * i] - q[3 * j], dy = q[3 * i + 1] - q[3 * j + 1], dz = q[3 * i + 2] - q[3 * j + 2];
                const double r2 = dx * dx + dy * dy + dz * dz + 1e-2, k = 1.0 / (r2 * std::sqrt(r2));
                f[3 * i] -= k * dx, f[3 * i + 1] -= k * dy, f[3 * i + 2] -= k * dz;
                f[3 * j] += k * dx, f[3 * j + 1] += k * dy, f[3 * j + 2] += k * dz;
            }
    }
};

template <class Potential, class Force>
struct by_hand {
    Potential V;
    Force F;
    template <class Vec> auto kinetic(const Vec& p) const { return p.squaredNorm() / 2; }
    template <class Vec> auto potential(const Vec& q) const { return V(q); }
    void force(const Eigen::VectorXd& q, Eigen::VectorXd& f) const { F(q, f); }
    void velocity(const Eigen::VectorXd& p, Eigen::VectorXd& v) const { v = p; }
};
template <class Potential, class Force>
struct force_by_hand {
    Potential V;
    Force F;
    template <class Vec> auto kinetic(const Vec& p) const { return p.squaredNorm() / 2; }
    template <class Vec> auto potential(const Vec& q) const { return V(q); }
    void force(const Eigen::VectorXd& q, Eigen::VectorXd& f) const { F(q, f); }
};

template <class H>
double seconds_for(const H& h, State x, long steps) {
    auto s = sympl::make_stepper<State>(h, sympl::method("leapfrog_kdk"));
    s.steps(x, 1e-3, 1);
    const auto t0 = std::chrono::steady_clock::now();
    s.steps(x, 1e-3, std::size_t(steps));
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() + 0 * x.q[0];
}

template <class Potential, class Force>
void compare(const char* system, long n, double work_per_step, State x, Potential V, Force F, int rounds, double budget) {
    const by_hand<Potential, Force> hand{V, F};
    const force_by_hand<Potential, Force> force{V, F};
    const auto lambdas = sympl::make_hamiltonian([](const auto& p) { return p.squaredNorm() / 2; },
                                                 [V](const auto& q) { return V(q); });
    const long steps = std::max(2L, long(budget / work_per_step));
    std::vector<double> r_force, r_lambdas, t_hand;
    for (int r = 0; r < rounds; ++r) {
        const double th = seconds_for(hand, x, steps), tf = seconds_for(force, x, steps),
                     tl = seconds_for(lambdas, x, steps);
        t_hand.push_back(th);
        r_force.push_back(tf / th);
        r_lambdas.push_back(tl / th);
    }
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    const double hand_ns = median(t_hand) * 1e9 / double(steps) / double(n);
    std::printf("%-8s n = %-8ld hand %7.2f ns   force %6.2fx   lambdas %6.2fx\n", system, n, hand_ns,
                median(r_force), median(r_lambdas));
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const int rounds = quick ? 3 : 5;
    std::printf("ns per particle per leapfrog step (hand), and each way of writing H as a multiple of it\n");
    for (long n : {100L, 1000L, 10000L, 100000L, 1000000L}) {
        if (quick && n > 100000) break;
        State x(n);
        for (long i = 0; i < n; ++i) x.q[i] = 0.1 * std::sin(0.3 * double(i));
        const sympl::hamiltonians::fpu_beta fpu{1.0};
        compare("fpu", n, double(n), x, [fpu](const auto& q) { return fpu.potential(q); },
                [fpu](const Eigen::VectorXd& q, Eigen::VectorXd& f) { fpu.force(q, f); }, rounds, quick ? 2e7 : 1e8);
    }
    for (long bodies : {100L, 300L, 1000L}) {
        if (quick && bodies > 300) break;
        State x(3 * bodies);
        for (long i = 0; i < 3 * bodies; ++i) x.q[i] = std::sin(1.7 * double(i)) * 3.0 + 0.01 * double(i % 7);
        compare("cluster", bodies, 10.0 * double(bodies * bodies), x, cluster_potential{}, cluster_force{}, rounds, quick ? 2e7 : 1e8);
    }
}
