// The long run: plain against compensated summation over up to 1e8 steps.
#include "study.hpp"

#include <algorithm>
#include <cmath>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

#include "output/format.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

using S1 = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

void long_run_study(const study_context& c) {
    const hamiltonians::pendulum h{};
    const S1 x0(V1(1.2), V1(0.3));
    const double e0 = energy(h, x0), dt = 0.001;
    const std::size_t last = c.quick ? 1000000 : 100000000;
    atomic_file csv(c.dir / "long_run.csv");
    csv.stream() << "steps,energy_error_plain,energy_error_compensated\n";
    c.summary << "## Long run: compensated summation\n\nPendulum, forest_ruth_4 at dt = 0.001 (truncation error ~1e-14), "
       << last << " steps. Relative energy error at each decade:\n\n| steps | plain | compensated |\n|---|---|---|\n";
    auto plain = make_stepper<S1>(h, method("forest_ruth_4"));
    auto kahan = make_stepper<S1>(h, method("forest_ruth_4"), stepper_options{true});
    S1 a = x0, b = x0;
    std::size_t done = 0;
    for (std::size_t target = 1000; target <= last; target *= 10) {
        c.bar.show("long run: " + std::to_string(target) + " steps");
        integrate_steps(plain, a, dt * double(done), dt, target - done);
        integrate_steps(kahan, b, dt * double(done), dt, target - done);
        done = target;
        const double ea = std::fabs(energy(h, a) - e0) / e0, eb = std::fabs(energy(h, b) - e0) / e0;
        csv.stream() << target << "," << ea << "," << eb << "\n";
        c.summary << "| " << target << " | " << format_number(ea, 3) << " | " << format_number(eb, 3) << " |\n";
    }
    c.summary << "\n";
    csv.commit();
}

}  // namespace sympl::app
