// Ensemble throughput: trajectory-steps per second per core, Henon-Heiles,
// for one trajectory at a time (the plain stepper loop, and run_ensemble<1>)
// and for W = native_double_width trajectories per SIMD state
// (run_ensemble<W>), side by side in one process, in interleaved rounds
// (median of the rounds), on one thread. Then the same ensemble on every
// core, per core. Prints the ratios.
//   bench_ensemble [--quick]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>

using namespace sympl;
using hh = hamiltonians::henon_heiles;
using state = phase_space<double, 2>;

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const std::size_t trajectories = quick ? 256 : 2048, steps = quick ? 1000 : 4000;
    const int rounds = quick ? 3 : 7;
    std::vector<state> starts;
    for (std::size_t i = 0; i < trajectories; ++i)  // regular and chaotic orbits of the E = 1/12 section
        starts.push_back(hh::initial_state(1.0 / 12, -0.3 + 0.6 * double(i) / double(trajectories), 0.05 * double(i % 7) - 0.15));
    std::printf("Henon-Heiles, %zu trajectories x %zu steps, dt = 0.05; W = native_double_width = %d; "
                "median of %d interleaved rounds, one thread\n\n", trajectories, steps, native_double_width, rounds);
    std::printf("%-16s %-30s %14s %10s\n", "method", "contender", "Mtraj-steps/s", "vs loop");
    double sink = 0;
    for (const char* name : {"leapfrog_kdk", "blanes_moan_s6"}) {
        const table m = method(name);
        for (const bool measured : {false, true}) {
            ensemble_options o;
            o.dt = 0.05;
            o.steps = steps;
            o.threads = 1;
            o.energy = measured;
            o.sample_every = measured ? 10 : steps;
            struct contender {
                std::string label;
                std::function<double()> run;
                std::vector<double> rates;
            };
            std::vector<contender> c;
            if (!measured)
                c.push_back({"one at a time: stepper loop", [&] {
                                 double s = 0;
                                 for (const state& x0 : starts) {
                                     state x = x0;
                                     auto st = make_stepper<state>(hh{}, m);
                                     st.steps(x, 0.05, steps);
                                     s += x.q[0];
                                 }
                                 return s;
                             }, {}});
            c.push_back({"one at a time: run_ensemble<1>", [&] { return run_ensemble<1>(hh{}, m, starts, o)[7].final_state.q[0]; }, {}});
            c.push_back({"batches: run_ensemble<W>", [&] { return run_ensemble(hh{}, m, starts, o)[7].final_state.q[0]; }, {}});
            for (int r = 0; r < rounds; ++r)
                for (auto& k : c) {
                    const double t0 = now();
                    sink += k.run();
                    k.rates.push_back(double(trajectories * steps) / (now() - t0) / 1e6);
                }
            const double base = median(c.front().rates);
            std::printf("%s, %s:\n", name, measured ? "energy error every 10 steps" : "nothing measured");
            for (auto& k : c)
                std::printf("%-16s %-30s %14.1f %9.2fx\n", "", k.label.c_str(), median(k.rates), median(k.rates) / base);
        }
    }
#ifdef _OPENMP
    const int cores = omp_get_num_procs();
    ensemble_options o;
    o.dt = 0.05;
    o.steps = steps;
    o.energy = false;
    o.sample_every = steps;
    std::vector<double> one, all;
    for (int r = 0; r < rounds; ++r) {
        o.threads = 1;
        double t0 = now();
        sink += run_ensemble(hh{}, method("blanes_moan_s6"), starts, o)[3].final_state.q[0];
        one.push_back(double(trajectories * steps) / (now() - t0) / 1e6);
        o.threads = cores;
        t0 = now();
        sink += run_ensemble(hh{}, method("blanes_moan_s6"), starts, o)[3].final_state.q[0];
        all.push_back(double(trajectories * steps) / (now() - t0) / 1e6 / cores);
    }
    std::printf("\nblanes_moan_s6 batches on %d threads: %.1f Mtraj-steps/s per core, %.2fx one thread's\n", cores,
                median(all), median(all) / median(one));
#endif
    std::printf("(checksum %g)\n", sink);
}
