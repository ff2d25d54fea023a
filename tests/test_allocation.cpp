// No heap allocation per step, fixed or dynamic state. Eigen allocates with
// malloc, so its own guard is used: with EIGEN_RUNTIME_NO_MALLOC, any Eigen
// heap allocation while set_is_malloc_allowed(false) trips eigen_assert, which
// this binary turns into an exception. Global operator new is counted too.
#include <atomic>
#include <cstdlib>
#include <new>
#include <stdexcept>

#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x) \
    do { if (!(x)) throw std::logic_error("Eigen: " #x); } while (false)

#include <doctest/doctest.h>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

namespace {
std::atomic<long> allocations{0};
}

void* operator new(std::size_t n) {
    ++allocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace sympl;

namespace {
// Heap allocations (Eigen's or operator new's) during 200 steps after the first.
template <class H, class State>
long allocations_during_steps(const H& h, State x, const char* name, bool compensated = false) {
    splitting_stepper<H, State> s(h, method(name), {compensated});
    s.step(x, 0.01);  // sizes the workspace (dynamic states)
    const long before = allocations.load();
    long eigen = 0;
    Eigen::internal::set_is_malloc_allowed(false);
    try {
        for (int i = 0; i < 100; ++i) s.step(x, 0.01);
        s.steps(x, 0.01, 100);
    } catch (const std::logic_error&) {
        eigen = 1;
    }
    Eigen::internal::set_is_malloc_allowed(true);
    return allocations.load() - before + eigen;
}
// Only energies: forces and velocities come from automatic differentiation.
struct autodiff_kepler {
    template <class V> auto kinetic(const V& p) const { return 0.5 * p.squaredNorm(); }
    template <class V> auto potential(const V& q) const { using std::sqrt; return -1.0 / sqrt(q.squaredNorm()); }
};
// The FPU chain's energies alone: its force comes from reverse mode (reverse_mode.hpp).
struct energies_only_fpu {
    hamiltonians::fpu_beta h{};
    template <class V> auto kinetic(const V& p) const { return h.kinetic(p); }
    template <class V> auto potential(const V& q) const { return h.potential(q); }
};
// A Hamiltonian whose force returns a fresh dynamic vector allocates every step.
struct allocating {
    template <class V> auto kinetic(const V& p) const { return 0.5 * p.squaredNorm(); }
    template <class V> auto potential(const V& q) const { return 0.5 * q.squaredNorm(); }
    Eigen::VectorXd force(const Eigen::VectorXd& q) const { return -q; }
};
}  // namespace

TEST_CASE("no heap allocation per step") {
    const auto kepler0 = hamiltonians::kepler::initial_state(0.5);
    CHECK(allocations_during_steps(hamiltonians::kepler{}, kepler0, "yoshida_6") == 0);
    CHECK(allocations_during_steps(hamiltonians::kepler{}, kepler0, "pefrl_4", true) == 0);
    CHECK(allocations_during_steps(autodiff_kepler{}, kepler0, "pefrl_4") == 0);
    phase_space<double> chain(Eigen::VectorXd::Constant(1000, 0.01), Eigen::VectorXd::Zero(1000));
    CHECK(allocations_during_steps(hamiltonians::fpu_beta{}, chain, "blanes_moan_s6") == 0);
    CHECK(allocations_during_steps(hamiltonians::fpu_beta{}, chain, "leapfrog_kdk", true) == 0);
    phase_space<double> rel(Eigen::VectorXd::Constant(20, 0.3), Eigen::VectorXd::Constant(20, 0.1));
    CHECK(allocations_during_steps(hamiltonians::relativistic_pendulum{}, rel, "forest_ruth_4") == 0);
    phase_space<double> dyn_kepler(kepler0.q, kepler0.p);
    CHECK(allocations_during_steps(autodiff_kepler{}, dyn_kepler, "leapfrog_kdk") == 0);
    // 1000 components: the force by reverse mode, whose tape keeps its memory.
    CHECK(allocations_during_steps(energies_only_fpu{}, chain, "leapfrog_kdk") == 0);
}

TEST_CASE("the guards work: a dynamic temporary is caught") {
    phase_space<double> x(Eigen::VectorXd::Constant(8, 0.1), Eigen::VectorXd::Zero(8));
    CHECK(allocations_during_steps(allocating{}, x, "leapfrog_kdk") >= 1);
}
