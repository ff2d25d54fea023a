// References: exact, or a long-double Sofroniou-Spaletta 10 run, cached on disk.
#include "report/reference.hpp"

#include <chrono>
#include <fstream>
#include <functional>
#include <future>
#include <iomanip>
#include <sstream>

#include "output/format.hpp"
#include "running/systems.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

reference_state make_reference(const scene& s, const runnable_system& p, const run_plan& plan, const fs::path& cache,
                               bool side_by_side) {
    if (p.exact) return {p.exact(s.t_end - s.t0), 0.0, "exact", {}};
    const double dt = plan.reference_dt, finest_dt = plan.finest_dt;
    const std::string kind = p.reference_method + ", dt = " + format_number(dt);
    // Cached on disk under a key of everything the reference depends on.
    std::ostringstream key;
    key << std::setprecision(17) << s.system << ';' << s.t0 << ';' << s.t_end << ';' << dt;
    for (const auto& [k, v] : s.parameters) key << ';' << k << '=' << v;
    for (double v : p.x0) key << ';' << v;
    const fs::path file =
        cache.empty() ? fs::path() : cache / ("reference_" + std::to_string(std::hash<std::string>{}(key.str())) + ".txt");
    if (!file.empty() && fs::exists(file)) {
        std::ifstream in(file);
        std::string stored;
        std::getline(in, stored);
        reference_state r{{}, 0, kind + " (cached)", {}};
        double v;
        if (stored == key.str() && in >> r.error) {
            while (in >> v) r.x.push_back(v);
            if (r.x.size() == p.x0.size()) return r;
        }
    }
    std::vector<double> coarse, fine;
    try {
        // The coarse run on a thread of its own, with a system of its own
        // (the runs share no system object), while this one runs the fine.
        std::future<std::vector<double>> coarse_run = std::async(
            side_by_side ? std::launch::async : std::launch::deferred, [&s, dt, x0 = p.x0] {
                const runnable_system own = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
                return own.reference(s.t0, s.t_end, 2 * dt, x0);
            });
        fine = p.reference(s.t0, s.t_end, dt, p.x0);
        coarse = coarse_run.get();
    } catch (const integration_error& e) {
        return {{}, -1, kind, "the reference (" + kind + ", a quarter of the finest step " + format_number(finest_dt) +
                                  ", and twice that) failed: " + e.what()};
    }
    reference_state r{fine, relative_difference(coarse, fine), kind, {}};
    if (!file.empty()) {
        fs::create_directories(cache);
        atomic_file out(file);
        out.stream() << key.str() << "\n" << std::setprecision(17) << r.error << "\n";
        for (double v : r.x) out.stream() << v << "\n";
        out.commit();
    }
    return r;
}

reference_cost estimate_reference(const scene& s, const runnable_system& p, const run_plan& plan) {
    reference_cost c{plan.reference_steps, 0};
    if (p.exact || !(plan.reference_dt > 0)) return c;
    const double dt = plan.reference_dt, span = s.t_end - s.t0;
    // k steps, k growing fourfold, until they last 50 ms or cover an eighth of the span.
    for (double k = 1;; k *= 4) {
        const auto start = std::chrono::steady_clock::now();
        try {
            p.reference(s.t0, s.t0 + k * dt, dt, p.x0);
        } catch (const integration_error&) {
            return c;  // the reference itself will say so
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (seconds >= 0.05 || k * dt >= span / 8) {
            c.seconds = seconds / k * plan.reference_steps;
            return c;
        }
    }
}

}  // namespace sympl::app
