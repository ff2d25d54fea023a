// The program's generic path against its compiled one (src/running/generic_path.hpp):
// the same method, step and span through each, timed side by side in one
// process, rounds interleaved, with the program's own timing (src/report/timing.hpp).
// Built as the program is (CMake's Release flags, no -march): it links the
// program's library, whose runs these are.
//   bench_generic_path            FPU-beta N = 32 and Henon-Heiles, 4 methods each
//   bench_generic_path --quick    fewer rounds
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>

#include "running/generic_path.hpp"
#include "running/systems.hpp"

using namespace sympl::app;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// ns per step of one unobserved run of `name` at dt over [0, t_end].
double ns_per_step(const run_function& run, const runnable_system& p, const std::string& name, double dt, double t_end) {
    run_request rq;
    rq.dt = dt;
    rq.observed = false;
    rq.timing_repeats = 3;
    rq.min_measurement = 0.05;
    const run_result r = run(*resolve_method(name, {}), rq, 0.0, t_end, p.x0);
    const double steps = t_end / dt;
    return r.seconds / steps * 1e9;
}

void compare(const char* label, const runnable_system& p, const run_function& generic, double dt, double t_end, int rounds) {
    std::printf("%s (dt = %g, %g steps a run)\n", label, dt, t_end / dt);
    std::printf("  %-18s %14s %14s %8s\n", "method", "compiled ns", "generic ns", "ratio");
    for (const char* name : {"leapfrog_kdk", "blanes_moan_s6", "dprkn8", "rk4"}) {
        std::vector<double> compiled, erased, ratios;
        for (int k = 0; k < rounds; ++k) {
            const double a = ns_per_step(p.runner, p, name, dt, t_end);
            const double b = ns_per_step(generic, p, name, dt, t_end);
            compiled.push_back(a);
            erased.push_back(b);
            ratios.push_back(b / a);
        }
        std::printf("  %-18s %14.1f %14.1f %8.2f\n", name, median(compiled), median(erased), median(ratios));
    }
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const int rounds = quick ? 3 : 9;
    const runnable_system chain = make_system("fpu_beta", {{"n", 32}}, {}, {}, "bench");
    const auto chain_generic = detail::generic_run(erased_separable::of(sympl::hamiltonians::fpu_beta{1}), chain.energy);
    compare("FPU-beta, N = 32", chain, chain_generic, 0.05, 200, rounds);
    const runnable_system hh = make_system("henon_heiles", {}, {}, {}, "bench");
    const auto hh_generic = detail::generic_run(erased_separable::of(sympl::hamiltonians::henon_heiles{}), hh.energy);
    compare("Henon-Heiles", hh, hh_generic, 0.05, 500, rounds);
    std::printf("ratio: generic / compiled, median of %d interleaved rounds\n", rounds);
}
