// The program's generic path against its compiled one (src/running/generic_path.hpp),
// and the same system written as formulas (src/formulas/, compiled once at
// start-up as a scene's would be): the same method, step and span through
// each, timed side by side in one process, rounds interleaved, with the
// program's own timing (src/report/timing.hpp).
// Built as the program is (CMake's Release flags, no -march): it links the
// program's library, whose runs these are.
// The four-body cluster's compiled run is examples/own_program's C++ system
// (planar_cluster.hpp), compiled here as sympl_add_program compiles it.
//   bench_generic_path            FPU-beta N = 32, Henon-Heiles, the pendulum
//                                 and the cluster, 4 methods each
//   bench_generic_path --quick    fewer rounds
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

#include "planar_cluster.hpp"

#include "formulas/formula_entry.hpp"
#include "running/generic_path.hpp"
#include "running/runnable.hpp"
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

void compare(const char* label, const runnable_system& p, const run_function& generic, const runnable_system& formulas,
             double dt, double t_end, int rounds) {
    std::printf("%s (dt = %g, %g steps a run)\n", label, dt, t_end / dt);
    std::printf("  %-16s %11s %11s %11s %9s %9s\n", "method", "compiled ns", "generic ns", "formula ns", "generic/",
                "formula/");
    for (const char* name : {"leapfrog_kdk", "blanes_moan_s6", "dprkn8", "rk4"}) {
        std::vector<double> compiled, erased, written, ratios, formula_ratios;
        for (int k = 0; k < rounds; ++k) {
            const double a = ns_per_step(p.runner, p, name, dt, t_end);
            const double b = ns_per_step(generic, p, name, dt, t_end);
            const double c = ns_per_step(formulas.runner, formulas, name, dt, t_end);
            compiled.push_back(a);
            erased.push_back(b);
            written.push_back(c);
            ratios.push_back(b / a);
            formula_ratios.push_back(c / a);
        }
        std::printf("  %-16s %11.1f %11.1f %11.1f %9.2f %9.2f\n", name, median(compiled), median(erased),
                    median(written), median(ratios), median(formula_ratios));
    }
}

// The system as a scene's [system] table would write it (examples/formulas/).
runnable_system formula_system(sympl::app::formulas::formula_texts t, const std::vector<double>& x0) {
    const std::size_t n = x0.size() / 2;
    t.q0.assign(x0.begin(), x0.begin() + long(n));
    t.p0.assign(x0.begin() + long(n), x0.end());
    sympl::app::formulas::define_formula_system(t);
    return make_system(t.name, {}, {}, {}, "bench");
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const int rounds = quick ? 3 : 9;
    const runnable_system chain = make_system("fpu_beta", {{"n", 32}}, {}, {}, "bench");
    const auto chain_generic = detail::generic_run(erased_separable::of(sympl::hamiltonians::fpu_beta{1}), chain.energy);
    sympl::app::formulas::formula_texts fpu;
    fpu.name = "fpu_formulas";
    fpu.parameters = {{"beta", 1.0}, {"n", 32}};
    fpu.T = "sum(i, 0, n - 1, p[i]^2/2)";
    fpu.V = "q[0]^2/2 + beta*q[0]^4/4 + sum(i, 0, n - 2, (q[i+1] - q[i])^2/2 + beta*(q[i+1] - q[i])^4/4)"
            " + q[n-1]^2/2 + beta*q[n-1]^4/4";
    compare("FPU-beta, N = 32", chain, chain_generic, formula_system(fpu, chain.x0), 0.05, 200, rounds);
    const runnable_system hh = make_system("henon_heiles", {}, {}, {}, "bench");
    const auto hh_generic = detail::generic_run(erased_separable::of(sympl::hamiltonians::henon_heiles{}), hh.energy);
    sympl::app::formulas::formula_texts hhf;
    hhf.name = "hh_formulas";
    hhf.coordinates = {"x", "y"};
    hhf.T = "(px^2 + py^2) / 2";
    hhf.V = "(x^2 + y^2) / 2 + x^2*y - y^3/3";
    compare("Henon-Heiles", hh, hh_generic, formula_system(hhf, hh.x0), 0.05, 500, rounds);
    const runnable_system pendulum = make_system("pendulum", {}, {}, {}, "bench");
    const auto pendulum_generic =
        detail::generic_run(erased_separable::of(sympl::hamiltonians::pendulum{}), pendulum.energy);
    sympl::app::formulas::formula_texts pf;
    pf.name = "pendulum_formulas";
    pf.parameters = {{"m", 1.0}, {"l", 1.0}, {"g", 1.0}};
    pf.coordinates = {"theta"};
    pf.T = "ptheta^2 / (2*m*l^2)";
    pf.V = "m*g*l*(1 - cos(theta))";
    compare("pendulum", pendulum, pendulum_generic, formula_system(pf, pendulum.x0), 0.1, 1000, rounds);
    // examples/own_program/planar_cluster.cpp's row, compiled for the kinds it names.
    using enum method_kind;
    constexpr compiled own{.kinds = {table, dprkn, odeint}};
    const runnable_system cluster = runnable<Eigen::Dynamic, own>(
        my::planar_cluster{}, {1.05, 0, 0.95, 0, -1, 0.05, -1, -0.05, 0, 2.9431747586863373, 0, -1.5289611963132423,
                               -2.23606797749979, -0.7071067811865476, 2.23606797749979, -0.7071067811865476});
    const auto cluster_generic = detail::generic_run(erased_separable::of(my::planar_cluster{}), cluster.energy);
    sympl::app::formulas::formula_texts cf;  // examples/formulas/cluster.toml
    cf.name = "cluster_formulas";
    cf.parameters = {{"G", 1.0}, {"m", 1.0}, {"bodies", 4}};
    cf.T = "sum(i, 0, 2*bodies - 1, p[i]^2 / (2*m))";
    cf.V = "sum(i, 0, bodies - 2, sum(j, i + 1, bodies - 1, -G*m*m / sqrt((q[2*i] - q[2*j])^2 + "
           "(q[2*i+1] - q[2*j+1])^2)))";
    compare("four-body cluster", cluster, cluster_generic, formula_system(cf, cluster.x0), 0.001, 2, rounds);
    std::printf("ratios: generic / compiled and formula / compiled, medians of %d interleaved rounds\n", rounds);
}
