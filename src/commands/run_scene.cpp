// The single-scene run.
#include "commands/run_scene.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <iomanip>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "output/format.hpp"
#include "report/loop_area.hpp"
#include "output/output_set.hpp"
#include "report/reference.hpp"
#include "methods/run_plan.hpp"
#include "studies/study.hpp"
#include "running/systems.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

struct outcome {
    const method_spec* method;
    run_result r;
    double final_error = -1;
    double loop_area_error = -1;
};

// An error of order one: the run has no correct digit (scene.hpp).
bool error_order_one(const outcome& o) {
    return o.final_error >= order_one_error || o.r.max_energy_error >= order_one_error;
}

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
    if (r.stable) j["error_order_one"] = error_order_one(o);
    j["reference"] = ref.kind;
    if (!ref.failure.empty()) j["reference_failure"] = ref.failure;
    j["seconds"] = std::max(r.seconds, 0.0);
    j["path"] = r.generic ? "generic" : "compiled";  // generic_path.hpp
    if (s.output.final_state && r.stable) j["final_state"] = r.final_state;
    return j;
}

std::string as_text(const scene& s, const outcome& o) {
    const run_result& r = o.r;
    std::ostringstream l;
    l << std::left << std::setw(24) << o.method->name;
    if (!r.stable) {
        l << "UNSTABLE: " << r.failure;
        if (s.output.writes_trajectory()) l << " (the trajectory file ends there with a '# truncated' line)";
        return l.str();
    }
    l << std::right << std::setw(10) << r.steps << " steps" << std::setw(12) << r.force_evaluations
      << " forces   energy error " << std::setw(10)
      << (r.max_energy_error >= 0 ? format_number(r.max_energy_error, 3) : "-") << "   final error " << std::setw(10)
      << (o.final_error >= 0 ? format_number(o.final_error, 3) : "-") << "   "
      << (r.seconds >= 0 ? format_number(r.seconds * 1e3, 3) + " ms" : std::string("(not timed)"));
    if (o.loop_area_error >= 0) l << "   loop area error " << format_number(o.loop_area_error, 3);
    if (r.generic) l << "   (generic path: not compiled for this system)";
    if (error_order_one(o))
        l << "\n    ^ ERROR OF ORDER ONE (>= " << format_number(order_one_error) << "): no correct digit, not a result; "
          << "a smaller dt";
    if (s.output.final_state) {
        l << "\n    final state:";
        for (double v : r.final_state) l << " " << format_number(v, 17);
    }
    return l.str();
}

// One method's checkpoint, FILE.<method>, and its trajectory's rows so far.
fs::path checkpoint_file(const scene& s, const scene_method& m) {
    return s.checkpoint.file + "." + file_name_part(m.name);
}
fs::path checkpoint_trajectory_file(const scene& s, const scene_method& m) {
    return checkpoint_file(s, m).string() + ".trajectory";
}

// A checkpoint's trajectory is written in place: one that is a symlink
// (planted there) is refused, never written through.
void refuse_planted_symlink(const scene& s, const fs::path& file) {
    std::error_code ec;
    if (fs::is_symlink(file, ec))
        throw error(printable(s.source) + ": checkpoint trajectory " + printable(file.string()) +
                    " is a symlink; expected a file this program made there (or none): it writes no file through a "
                    "symlink; remove it");
}

// One method's checkpoints: FILE.<method> and, when the scene writes a
// trajectory, the rows so far in FILE.<method>.trajectory (the checkpoint
// records how many bytes of it belong to the run).
class checkpointed_method {
public:
    checkpointed_method(const scene& s, const scene_method& m, double dt, bool resume, std::string trajectory_header,
                        std::size_t state_size)
        : s_(&s), m_(&m), dt_(dt), file_(checkpoint_file(s, m)), trajectory_file_(checkpoint_trajectory_file(s, m)),
          with_trajectory_(!trajectory_header.empty()) {
        if (file_.has_parent_path()) fs::create_directories(file_.parent_path());
        remove_stale_temporaries();
        if (resume && fs::exists(file_)) {
            from_ = read_checkpoint(file_, s.text_hash, m.name, dt);
            // An extrapolated method's step count is its own (inner steps): only its time is held to the span.
            check_checkpoint_fields(*from_, file_, state_size, s.t0, s.t_end,
                                    steps_in_physical_time(m) && m.extrapolation_columns == 0);
        }
        if (!with_trajectory_) return;
        // Written only as a file this program made: never through a symlink
        // (a planted one would have its target overwritten), resumed only
        // from a regular file.
        refuse_planted_symlink(s, trajectory_file_);
        if (from_) {
            std::error_code ec;
            const auto size = fs::file_size(trajectory_file_, ec);
            if (ec || size < from_->trajectory_bytes)
                throw error("checkpoint " + printable(file_.string()) + ": its trajectory " + printable(trajectory_file_.string()) +
                            " is shorter than the " + std::to_string(from_->trajectory_bytes) +
                            " bytes it recorded; not resumed from (remove both to start over)");
            // Its rows end where the record says: at a line's end, the header's at least.
            char last = '\n';
            if (from_->trajectory_bytes > 0) {
                std::ifstream rows(trajectory_file_, std::ios::binary);
                rows.seekg(std::streamoff(from_->trajectory_bytes - 1));
                rows.get(last);
            }
            if (from_->trajectory_bytes < trajectory_header.size() || last != '\n')
                throw error("checkpoint " + printable(file_.string()) + ": it records " + std::to_string(from_->trajectory_bytes) +
                            " bytes of " + printable(trajectory_file_.string()) + ", which is not the end of a row; expected a "
                            "row's end; not resumed from (remove both to start over)");
            fs::resize_file(trajectory_file_, from_->trajectory_bytes);  // rows written after the checkpoint go
            trajectory_.open(trajectory_file_, std::ios::binary | std::ios::app);
        } else {
            // New (O_EXCL | O_NOFOLLOW), a killed run's leftover replaced, then opened by name.
            const int fd = create_new_file(trajectory_file_);
            if (fd < 0)
                throw error("cannot write " + printable(trajectory_file_.string()) + ": " + std::strerror(errno));
            ::close(fd);
            trajectory_.open(trajectory_file_, std::ios::binary | std::ios::trunc);
            trajectory_ << trajectory_header;
        }
        trajectory_ << std::setprecision(17);
        if (!trajectory_) throw error("cannot write " + printable(trajectory_file_.string()) + ": " + std::strerror(errno));
    }

    // Points the run at the checkpoint's trajectory and save/resume hooks.
    void attach(run_request& rq) {
        rq.checkpoint.every_steps = s_->checkpoint.every_steps;
        rq.checkpoint.resume = from_ ? &*from_ : nullptr;
        rq.checkpoint.resume_file = file_.string();
        if (with_trajectory_) rq.trajectory = &trajectory_;
        rq.checkpoint.save = [this](checkpoint_record& r) {
            r.scene_hash = s_->text_hash;
            r.method = m_->name;
            r.dt = dt_;
            if (with_trajectory_) {
                trajectory_.flush();
                if (!trajectory_) throw error("could not write " + printable(trajectory_file_.string()) + ": " + std::strerror(errno));
                r.trajectory_bytes = std::uint64_t(trajectory_.tellp());
            }
            write_checkpoint(file_, r);
            saved_ = true;
        };
    }

    // The whole trajectory of the run, into the output file.
    void copy_trajectory(std::ostream& out) {
        trajectory_.close();
        std::ifstream in(trajectory_file_, std::ios::binary);
        out.seekp(0);  // the output file had only the header, which the checkpoint's file starts with too
        out << in.rdbuf();
    }

    // The run is complete: its checkpoint and trajectory go, and only what
    // this run wrote or resumed from (a regular file, never a symlink).
    void remove() {
        std::error_code ec;
        const auto ours = [&](const fs::path& f) { return fs::symlink_status(f, ec).type() == fs::file_type::regular; };
        if ((saved_ || from_) && ours(file_)) fs::remove(file_, ec);
        if (with_trajectory_ && ours(trajectory_file_)) fs::remove(trajectory_file_, ec);
    }

    // FILE.<method>.sympl-part-PID of a process killed while writing a
    // checkpoint: a regular file of that exact form, never a symlink.
    void remove_stale_temporaries() const {
        const std::string prefix = file_.filename().string() + ".sympl-part-";
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(file_.has_parent_path() ? file_.parent_path() : ".", ec)) {
            const std::string name = entry.path().filename().string();
            if (name.rfind(prefix, 0) != 0 || !is_temporary_name(name) || !entry.is_regular_file(ec) ||
                entry.is_symlink(ec))
                continue;
            const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
            if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove(entry.path(), ec);
        }
    }

private:
    const scene* s_;
    const scene_method* m_;
    double dt_;
    fs::path file_, trajectory_file_;
    bool with_trajectory_;
    bool saved_ = false;  // a checkpoint of this run was written
    std::optional<checkpoint_record> from_;
    std::ofstream trajectory_;
};

}  // namespace

namespace {

// t, then the state's columns as everywhere else (q1..qn, p1..pn, or bodies' names).
std::vector<std::string> trajectory_header(const runnable_system& p) {
    std::vector<std::string> header{"t"};
    for (auto& column : state_columns(p.system, p.degrees_of_freedom)) header.push_back(std::move(column));
    return header;
}

// <scene>_<method>_energy.csv: t and the relative energy error every k
// steps, written by the run as it goes (staged; nothing held in memory).
std::unique_ptr<atomic_file> energy_series_file(const fs::path& file) {
    auto out = std::make_unique<atomic_file>(file);
    out->stream() << "t,energy_error\n" << std::setprecision(17);
    return out;
}

// One planned run: its trajectory file (staged), its checkpoints, its measures.
outcome run_one(const scene& s, const runnable_system& p, const planned_run& planned, const reference_state& ref,
                const fs::path& dir, bool resume, const progress& bar, std::vector<std::unique_ptr<atomic_file>>& files,
                std::vector<checkpointed_method>& finished_checkpoints) {
    const scene_method& m = *planned.method;
    run_request rq = planned.request();
    rq.energy = s.output.energy_error && p.hamiltonian;
    rq.energy_series_every = rq.energy ? s.output.energy_every : 0;
    rq.timing_repeats = s.checkpoint.every_steps ? 0 : 1;  // a checkpointed run is not timed a second time
    if (bar.tty)
        rq.progress = [&](double t) {
            bar.show("  " + m.name + ": t = " + format_number(t, 6) + " of " + format_number(s.t_end, 6) + " (" +
                     format_number(100 * (t - s.t0) / (s.t_end - s.t0), 3) + "%)");
        };
    std::unique_ptr<atomic_file> trajectory;
    const std::string header = csv_line(trajectory_header(p));
    if (s.output.writes_trajectory()) {
        trajectory = std::make_unique<atomic_file>(dir / (file_name_part(s.name) + "_" + file_name_part(m.name) +
                                                          "_trajectory.csv"));
        trajectory->stream() << header << std::setprecision(17);
        rq.trajectory = &trajectory->stream();
        rq.trajectory_every = s.output.trajectory_every;
        rq.output_times = s.output.times;
        rq.output_order = p.form.quadratic_kinetic ? 5 : 3;
    }
    std::unique_ptr<atomic_file> energy_series;
    if (rq.energy_series_every) {
        energy_series = energy_series_file(dir / (file_name_part(s.name) + "_" + file_name_part(m.name) + "_energy.csv"));
        rq.energy_series_file = &energy_series->stream();
    }
    std::optional<checkpointed_method> checkpoints;
    if (s.checkpoint.every_steps) {
        checkpoints.emplace(s, m, rq.dt, resume, trajectory ? header : std::string(), p.x0.size());
        checkpoints->attach(rq);
    }
    outcome o{&m, p.run(m, rq, s.t0, s.t_end, p.x0)};
    if (checkpoints && trajectory) checkpoints->copy_trajectory(trajectory->stream());
    if (trajectory && !o.r.stable)  // a comment line (gnuplot and CSV readers with '#' comments skip it)
        trajectory->stream() << "# truncated: " << o.r.failure << "\n";
    if (trajectory) files.push_back(std::move(trajectory));
    if (energy_series) {
        if (!o.r.stable) energy_series->stream() << "# truncated: " << o.r.failure << "\n";
        files.push_back(std::move(energy_series));
    }
    if (checkpoints) finished_checkpoints.push_back(std::move(*checkpoints));
    if (o.r.stable && !ref.x.empty()) o.final_error = relative_difference(o.r.final_state, ref.x);
    if (o.r.stable && s.output.loop_area) o.loop_area_error = loop_area_error(p, m, rq, s.t0, s.t_end);
    return o;
}

// The summary's first lines: what ran, against which reference; a sweep says
// which of its values `sympl run` takes.
// Times and steps as the scene wrote them (shortest: 0.05, not 0.050000000000000003);
// a tolerance only where an adaptive method uses one.
void write_heading(const scene& s, const run_plan& plan, const reference_state& ref, std::ostream& out) {
    bool fixed = false, controlled = false;
    for (const scene_method& m : s.methods) (adaptive(m) ? controlled : fixed) = true;
    out << s.name << ": " << s.system << ", t = " << shortest(s.t0) << " .. " << shortest(s.t_end);
    if (s.period > 0) out << " (" << format_number((s.t_end - s.t0) / s.period, 6) << " periods)";
    if (fixed) out << ", dt = " << shortest(s.dt.front());
    if (controlled) out << ", tolerance " << shortest(s.tolerances.front());
    out << ", reference: " << ref.kind;
    if (ref.error > 0) out << " (its own error ~" << format_number(ref.error, 2) << ")";
    out << "\n";
    std::vector<std::string> swept;
    for (const scene_method& m : s.methods)
        if (sweep_of(s, m).size() > plan.sweep_length(m)) swept.push_back(m.name);
    if (!swept.empty()) {
        out << "  (a sweep: ";
        for (std::size_t i = 0; i < swept.size(); ++i) out << (i ? ", " : "") << swept[i];
        out << (swept.size() == 1 ? " runs its" : " run their") << " first, largest, " << (fixed ? "dt" : "tolerance")
            << (fixed && controlled ? " or tolerance" : "") << " here; `sympl report` runs them all)\n";
    }
    if (s.output.times_dropped)
        out << "  (" << s.output.times_dropped << " of the output times are past t_end = " << shortest(s.t_end)
            << " and have no rows)\n";
    if (!ref.failure.empty()) out << "  no final errors: " << ref.failure << "\n";
}

}  // namespace

// The reference a run's final errors need, said on stderr before it starts
// when it is long, refused up front when absurd; none when the scene does not
// ask for final errors (and has no exact solution, which is free).
reference_state reference_for_run(const scene& s, const runnable_system& p, const run_plan& plan, double max_steps) {
    const bool asked = s.output.final_error.value_or(bool(p.exact));
    if (!asked)
        return {{}, 0,
                p.exact ? std::string("none (output.final_error = false)")
                        : "none (output.final_error = true measures final errors against " + p.reference_method + ")",
                {}};
    if (p.exact) return make_reference(s, p, plan);
    const reference_cost cost = estimate_reference(s, p, plan);
    const std::string what = "the reference for the final errors (" + p.reference_method + ", dt = " +
                             shortest(plan.reference_dt) + ", " + format_number(cost.steps, 3) + " steps of " +
                             std::to_string(p.degrees_of_freedom) + " degrees of freedom) takes about " +
                             format_number(cost.seconds, 2) + " s";
    const double limit = max_reference_seconds * max_steps / default_max_steps;
    if (cost.seconds > limit)
        throw scene_error(printable(s.source) + ": " + what + ", measured on its first steps; the limit is " +
                          format_number(limit, 3) + " s (leave output.final_error out, or raise it with --max-steps)");
    if (cost.seconds > announced_reference_seconds)
        std::cerr << "sympl: " << what << ", before the methods run (leave output.final_error out to skip it)"
                  << std::endl;
    return make_reference(s, p, plan);
}

namespace {

// The nearest folder at or above `path` that exists (an output directory is
// made by the run): the file system its files will go to.
fs::path existing_folder(fs::path path) {
    std::error_code ec;
    path = fs::absolute(path.empty() ? fs::path(".") : path, ec);
    while (!fs::is_directory(path, ec) && path.has_relative_path()) path = path.parent_path();
    return path;
}

// The bytes of the checkpoints' trajectories a resumed run finds written.
double written_before(const scene& s, const run_plan& plan) {
    double bytes = 0;
    std::error_code ec;
    for (const planned_run& r : plan.runs) {
        if (const auto size = fs::file_size(checkpoint_trajectory_file(s, *r.method), ec); !ec) bytes += double(size);
    }
    return bytes;
}

}  // namespace

output_disk_use disk_use_of(const scene& s, const run_plan& plan, const runnable_system& p) {
    const output_spec& o = s.output;
    output_disk_use u;
    for (const planned_run& r : plan.runs) {
        // A row per outer step (an extrapolated method's inner steps write
        // none); one for a run that chooses its own steps.
        const double steps = r.steps > 0 ? std::ceil((s.t_end - s.t0) / r.dt) : 0;
        if (o.trajectory_every) u.trajectory_rows += std::floor(steps / double(o.trajectory_every)) + 1;
        u.trajectory_rows += double(o.times.size());
        if (o.energy_every && o.energy_error && p.hamiltonian)
            u.energy_rows += std::floor(steps / double(o.energy_every)) + 1;
    }
    u.columns = 1 + p.x0.size();
    const double trajectory = u.trajectory_rows * double(u.columns) * u.bytes_a_number;
    const double energy = u.energy_rows * 2 * u.bytes_a_number;
    if (o.writes_files()) u.places.push_back({existing_folder(o.directory), "output.directory", trajectory + energy});
    if (s.checkpoint.every_steps && o.writes_trajectory())
        u.places.push_back({existing_folder(fs::path(s.checkpoint.file).parent_path()), "checkpoint.file", trajectory});
    return u;
}

void check_disk_use(const scene& s, const output_disk_use& u,
                    const std::function<free_space(const fs::path&)>& space_of, double already_written) {
    std::vector<free_space> spaces;
    for (const output_disk_use::place& place : u.places) spaces.push_back(space_of(place.folder));
    for (std::size_t i = 0; i < u.places.size(); ++i) {
        if (!spaces[i].known) continue;  // unknown: not refused on a guess
        // Every place on this file system counts against its free space; a
        // resumed checkpoint's trajectory is partly written already.
        double bytes = 0;
        for (std::size_t j = 0; j < u.places.size(); ++j)
            if (spaces[j].known && spaces[j].device == spaces[i].device)
                bytes += u.places[j].bytes - (u.places[j].key == "checkpoint.file" ? already_written : 0);
        if (bytes <= spaces[i].available) continue;
        throw scene_error(printable(s.source) + ": the run's files would take about " + format_number(bytes / 1e9, 3) +
                          " GB (" + format_number(u.trajectory_rows, 3) + " trajectory rows of " +
                          std::to_string(u.columns) + " numbers, " + format_number(u.energy_rows, 3) +
                          " energy rows, about " + format_number(u.bytes_a_number, 2) + " bytes a number) where " +
                          u.places[i].key + "'s file system (" + printable(u.places[i].folder.string()) + ") has " +
                          format_number(spaces[i].available / 1e9, 3) +
                          " GB free; expected fewer rows (a larger output.trajectory_every or output.energy_every)");
    }
}

free_space free_space_of(const fs::path& folder) {
    struct stat st;
    std::error_code ec;
    const fs::space_info space = fs::space(folder, ec);
    if (ec || ::stat(folder.c_str(), &st) != 0) return {};
    return {.known = true, .device = std::uint64_t(st.st_dev), .available = double(space.available)};
}

// A checkpoint's trajectory is written in place (checkpointed_method): one
// that is a symlink is refused before any method runs, so that nothing is
// written through it and nothing computed is lost to the refusal.
void check_no_planted_symlinks(const scene& s, const run_plan& plan) {
    if (!s.checkpoint.every_steps || !s.output.writes_trajectory()) return;
    for (const planned_run& r : plan.runs) {
        refuse_planted_symlink(s, checkpoint_trajectory_file(s, *r.method));
    }
}

void run_scene(const scene& s, bool json, std::ostream& out, double max_steps, bool resume) {
    const runnable_system p = system_of(s);
    run_plan plan = plan_runs(s, p, sweep_use::first);
    if (!s.output.final_error.value_or(bool(p.exact))) plan.reference_dt = plan.reference_steps = 0;  // none runs
    check_run_size(plan, max_steps);
    if (s.output.energy_every && !p.hamiltonian)
        throw scene_error(printable(s.source) + ": output.energy_every: " + s.system + " has no energy (it is not Hamiltonian); "
                          "expected no energy_every");
    if (!s.output.times.empty() && !p.form.separable_hamiltonian)
        throw scene_error(printable(s.source) + ": output.times: " + s.system +
                          " is not a separable Hamiltonian T(p) + V(q), whose velocity and force the interpolant "
                          "between steps needs; use output.trajectory_every");
    if (resume && !s.checkpoint.every_steps)
        throw scene_error(printable(s.source) + ": --resume, but the scene has no checkpoint = {every_steps = N, file = \"...\"}");
    check_disk_use(s, disk_use_of(s, plan, p), free_space_of,
                   resume && s.checkpoint.every_steps ? written_before(s, plan) : 0);
    check_no_planted_symlinks(s, plan);
    const reference_state ref = reference_for_run(s, p, plan, max_steps);
    // Files, when the scene asks for any, are staged and moved into place together.
    std::optional<output_set> outputs;
    if (s.output.writes_files()) outputs.emplace(s.output.directory);
    const fs::path dir = outputs ? outputs->staging() : fs::path(s.output.directory);
    std::vector<outcome> outcomes;
    const progress bar;  // long runs show how far they are on a terminal
    std::vector<std::unique_ptr<atomic_file>> files;  // committed together at the end
    std::vector<checkpointed_method> finished_checkpoints;
    for (const planned_run& r : plan.runs)
        outcomes.push_back(run_one(s, p, r, ref, dir, resume, bar, files, finished_checkpoints));
    bar.done();
    for (auto& f : files) f->commit();
    if (outputs) outputs->commit();
    for (checkpointed_method& c : finished_checkpoints) c.remove();  // the run is complete: nothing to resume
    if (json) {
        nlohmann::json all = nlohmann::json::array();
        for (const outcome& o : outcomes) all.push_back(as_json(s, o, ref));
        out << all.dump(2) << "\n";
        return;
    }
    write_heading(s, plan, ref, out);
    for (const outcome& o : outcomes) out << "  " << as_text(s, o) << "\n";
}

}  // namespace sympl::app
