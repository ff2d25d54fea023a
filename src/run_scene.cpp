// The single-scene run.
#include "run_scene.hpp"

#include <algorithm>
#include <iomanip>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "format.hpp"
#include "loop_area.hpp"
#include "output_set.hpp"
#include "reference.hpp"
#include "studies/study.hpp"
#include "writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

struct outcome {
    const method_spec* method;
    run_result r;
    double final_error = -1;
    double loop_area_error = -1;
};

nlohmann::json as_json(const scene& s, const outcome& o, const reference_state& ref) {
    const run_result& r = o.r;
    nlohmann::json j = {{"scene", s.name}, {"method", o.method->name}, {"status", r.stable ? "stable" : "unstable"}};
    if (!r.stable) {
        j["blowup_step"] = r.blowup_step;
        j["blowup_time"] = r.blowup_time;
        j["failure"] = r.failure;
    }
    j["steps"] = r.steps;
    j["force_evaluations"] = r.force_evaluations;
    if (r.max_energy_error >= 0) j["max_energy_error"] = r.max_energy_error;
    if (o.final_error >= 0) j["final_error"] = o.final_error;
    if (o.loop_area_error >= 0) j["loop_area_error"] = o.loop_area_error;
    j["reference"] = ref.kind;
    if (!ref.failure.empty()) j["reference_failure"] = ref.failure;
    j["seconds"] = std::max(r.seconds, 0.0);
    if (s.output.final_state && r.stable) j["final_state"] = r.final_state;
    return j;
}

std::string as_text(const scene& s, const outcome& o) {
    const run_result& r = o.r;
    std::ostringstream l;
    l << std::left << std::setw(24) << o.method->name;
    if (!r.stable) {
        l << "UNSTABLE: " << r.failure;
        if (s.output.trajectory_every) l << " (the trajectory file ends there with a '# truncated' line)";
        return l.str();
    }
    l << std::right << std::setw(10) << r.steps << " steps" << std::setw(12) << r.force_evaluations
      << " forces   energy error " << std::setw(10)
      << (r.max_energy_error >= 0 ? format_number(r.max_energy_error, 3) : "-") << "   final error " << std::setw(10)
      << (o.final_error >= 0 ? format_number(o.final_error, 3) : "-") << "   " << format_number(r.seconds * 1e3, 3) << " ms";
    if (o.loop_area_error >= 0) l << "   loop area error " << format_number(o.loop_area_error, 3);
    if (s.output.final_state) {
        l << "\n    final state:";
        for (double v : r.final_state) l << " " << format_number(v, 17);
    }
    return l.str();
}

}  // namespace

void run_scene(const scene& s, bool json, std::ostream& out, double max_steps) {
    const problem p = problem_of(s);
    check_run_size(s, p, max_steps, false);
    // The reference resolves the steps this run takes (the first of each sweep).
    double finest = s.dt.front();
    for (const scene_method& m : s.methods)
        if (steps_in_physical_time(m)) finest = std::min(finest, sweep_of(s, m).front());
    const reference_state ref = make_reference(s, p, finest);
    // Files, when the scene asks for any, are staged and moved into place together.
    std::optional<output_set> outputs;
    if (s.output.trajectory_every) outputs.emplace(s.output.directory);
    const fs::path dir = outputs ? outputs->staging() : fs::path(s.output.directory);
    std::vector<outcome> outcomes;
    const progress bar;  // long runs show how far they are on a terminal
    std::vector<std::unique_ptr<atomic_file>> files;  // committed together at the end
    for (const scene_method& m : s.methods) {
        run_request rq;
        rq.dt = sweep_of(s, m).front();
        rq.tolerance = rq.dt;
        rq.energy = s.output.energy_error && p.hamiltonian;
        rq.timing_repeats = 1;
        if (bar.tty)
            rq.progress = [&](double t) {
                bar.show("  " + m.name + ": t = " + format_number(t, 6) + " of " + format_number(s.t_end, 6) + " (" +
                         format_number(100 * (t - s.t0) / (s.t_end - s.t0), 3) + "%)");
            };
        std::unique_ptr<atomic_file> trajectory;
        if (s.output.trajectory_every) {
            trajectory = std::make_unique<atomic_file>(dir / (file_name_part(s.name) + "_" + file_name_part(m.name) +
                                                              "_trajectory.csv"));
            std::vector<std::string> header{"t"};
            for (const char* coordinate : {"q", "p"})
                for (std::size_t i = 0; i < p.degrees_of_freedom; ++i) header.push_back(coordinate + std::to_string(i));
            trajectory->stream() << csv_line(header) << std::setprecision(17);
            rq.trajectory = &trajectory->stream();
            rq.trajectory_every = s.output.trajectory_every;
        }
        outcome o{&m, p.run(m, rq, s.t0, s.t_end, p.x0)};
        if (trajectory && !o.r.stable)  // a comment line (gnuplot and CSV readers with '#' comments skip it)
            trajectory->stream() << "# truncated: " << o.r.failure << "\n";
        if (trajectory) files.push_back(std::move(trajectory));
        if (o.r.stable && ref.failure.empty()) o.final_error = relative_difference(o.r.final_state, ref.x);
        if (o.r.stable && s.output.loop_area) o.loop_area_error = loop_area_error(p, m, rq, s.t0, s.t_end);
        outcomes.push_back(std::move(o));
    }
    bar.done();
    for (auto& f : files) f->commit();
    if (outputs) outputs->commit();
    if (json) {
        nlohmann::json all = nlohmann::json::array();
        for (const outcome& o : outcomes) all.push_back(as_json(s, o, ref));
        out << all.dump(2) << "\n";
        return;
    }
    out << s.name << ": " << s.system << ", t = " << format_number(s.t0, 17) << " .. " << format_number(s.t_end, 17)
        << ", dt = " << format_number(s.dt.front(), 17) << " (dopri5 tolerance " << format_number(s.tolerances.front())
        << "), reference: " << ref.kind;
    if (ref.error > 0) out << " (its own error ~" << format_number(ref.error, 2) << ")";
    out << "\n";
    if (!ref.failure.empty()) out << "  no final errors: " << ref.failure << "\n";
    for (const outcome& o : outcomes) out << "  " << as_text(s, o) << "\n";
}

}  // namespace sympl::app
