// The energy error along a run: symplectic tables against Odeint on a Kepler scene.
#include "study.hpp"

#include <algorithm>
#include <cmath>

#include <sympl/sympl.hpp>

#include "format.hpp"
#include "systems.hpp"
#include "writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

void energy_series_study(const std::vector<scene>& scenes, const fs::path& dir, bool plots) {
    // The energy error along the run for a few methods on the first Kepler scene (or the first Hamiltonian one).
    const scene* chosen = nullptr;
    for (const scene& s : scenes)
        if (s.system == "kepler") { chosen = &s; break; }
    if (!chosen) return;
    const problem p = make_problem(chosen->system, chosen->parameters, chosen->q0, chosen->p0, chosen->source);
    const double dt = chosen->dt[chosen->dt.size() / 2];
    atomic_file csv(dir / "energy_vs_time.csv");
    csv.stream() << "method,t,energy_error\n";
    std::vector<std::string> names;
    for (const std::string name : {"leapfrog_kdk", "blanes_moan_s6", "odeint_rk4", "odeint_dopri5"}) {
        const method_spec m = *resolve_method(name, {});
        run_request rq;
        rq.dt = dt;
        rq.tolerance = 1e-8;
        rq.energy = true;
        rq.energy_series_every = std::max<std::size_t>(1, std::size_t((chosen->t_end - chosen->t0) / dt / 400));
        rq.timing_repeats = 0;
        const run_result r = p.run(m, rq, chosen->t0, chosen->t_end, p.x0);
        for (const auto& [t, e] : r.energy_series) csv.stream() << name << "," << t << "," << e << "\n";
        names.push_back(name);
    }
    csv.commit();
    if (!plots) return;
    atomic_file gp(dir / "energy_vs_time.gp");
    gp.stream() << "set terminal pngcairo size 900,600\nset output " << gnuplot_string("energy_vs_time.png")
                << "\nset datafile separator ','\nset logscale y\nset format y '10^{%L}'\nset xlabel 't'\n"
                << "set ylabel 'relative energy error'\nset title "
                << gnuplot_string(chosen->name + ": dt = " + format_number(dt) + " (dopri5: tolerance 1e-8)")
                << " noenhanced\nset key outside noenhanced\nplot ";
    for (std::size_t i = 0; i < names.size(); ++i)
        gp.stream() << (i ? ", " : "") << gnuplot_string("energy_vs_time.csv") << " using (strcol(1) eq "
                    << gnuplot_string(names[i]) << " ? $2 : NaN):($3 > 0 ? $3 : NaN) with lines title "
                    << gnuplot_string(names[i]) << " noenhanced";
    gp.stream() << "\n";
    gp.commit();
    run_gnuplot(dir / "energy_vs_time.gp", dir / "energy_vs_time.png");
}

}  // namespace sympl::app
