// Extreme scales and precisions: the same Kepler orbit at L = 1e-20 .. 1e20 and in float .. long double.
#include "study.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/kepler.hpp>

#include "output/format.hpp"
#include "running/systems.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

template <class S>
double kepler_precision_error() {
    using K = phase_space<S, 2>;
    K x = hamiltonians::kepler::initial_state<S>(0.5);
    auto s = make_stepper<K>(hamiltonians::kepler{}, method("sofroniou_spaletta_10"));
    const S period = S(2) * std::numbers::pi_v<S>;
    integrate_until(s, x, S(0), period, S(period / S(200)));
    const K exact = hamiltonians::kepler::exact_state<S>(0.5, period);
    return double(max_difference(x, exact));
}

}  // namespace

void extreme_study(const study_context& c) {
    atomic_file csv(c.dir / "extreme_scales.csv");
    csv.stream() << "case,max_energy_error,final_error\n";
    c.summary << "## Extreme scales and precisions\n\nKepler e = 0.5, blanes_moan_s6, dt = period/2000, one period, in units "
          "where lengths are scaled by L (mu -> mu L^3): relative errors are the same at every scale.\n\n"
       << "| L | max energy error | final error |\n|---|---|---|\n";
    for (double L : {1e-20, 1.0, 1e20}) {
        const double period = 2 * std::numbers::pi;
        const runnable_system p = make_system("kepler", {{"scale", L}}, {}, {}, "extreme scales");
        run_request rq;
        rq.dt = period / 2000;
        rq.energy = true;
        rq.timing_repeats = 0;
        const run_result r = p.run(*resolve_method("blanes_moan_s6", {}), rq, 0, period, p.x0);
        const double fin = relative_difference(r.final_state, p.exact(period));
        csv.stream() << "L=" << L << "," << r.max_energy_error << "," << fin << "\n";
        c.summary << "| " << format_number(L) << " | " << format_number(r.max_energy_error, 6) << " | " << format_number(fin, 6) << " |\n";
    }
    c.summary << "\nThe same orbit with Sofroniou-Spaletta 10 at dt = period/200 in three precisions (final error in q, p):\n\n"
       << "| scalar | final error |\n|---|---|\n";
    const double ef = kepler_precision_error<float>(), ed = kepler_precision_error<double>(),
                 el = kepler_precision_error<long double>();
    c.summary << "| float | " << format_number(ef, 3) << " |\n| double | " << format_number(ed, 3) << " |\n| long double | " << format_number(el, 3) << " |\n\n";
    csv.stream() << "float," << "," << ef << "\ndouble,," << ed << "\nlong double,," << el << "\n";
    csv.commit();
}

}  // namespace sympl::app
