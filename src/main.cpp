// The sympl command-line program.
//   sympl tables [--json]            every catalog entry and its properties
//   sympl systems [--json]           every system, its parameters and the method kinds
//   sympl check-table --kick ... --drift ... [--convention ...] [--json]
//   sympl run SCENE.toml [--json]    one scene: summary and the outputs it asks for
//   sympl report [SCENE.toml ...] [--out DIR] [--quick]   the work-precision study
// Invalid input: exit code 2 and one line on stderr.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>

#include "coefficient_list.hpp"
#include "ensemble_run.hpp"
#include "mpi_exchange.hpp"
#include "format.hpp"
#include "interrupt.hpp"
#include "report.hpp"
#include "run_scene.hpp"
#include "scene.hpp"
#include "systems.hpp"

namespace {

std::vector<double> as_doubles(const std::vector<sympl::coefficient>& c) { return {c.begin(), c.end()}; }

using sympl::app::fixed;
using sympl::app::format_number;
using sympl::app::scientific;

// The registries: systems (with parameters) and method kinds.
void print_systems(bool json) {
    using namespace sympl::app;
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& s : systems()) {
            nlohmann::json params = nlohmann::json::array();
            for (const auto& p : s.parameters)
                params.push_back({{"name", p.name}, {"default", p.value}, {"expected", p.expected()}, {"meaning", p.meaning}});
            out.push_back({{"name", s.name}, {"description", s.description}, {"exact", s.exact}, {"parameters", params}});
        }
        std::cout << out.dump(2) << "\n";
        return;
    }
    for (const auto& s : systems()) {
        std::cout << s.name << (s.exact ? "  (exact solution)" : "") << "\n    " << s.description << "\n";
        for (const auto& p : s.parameters)
            std::cout << "    " << std::left << std::setw(16) << p.name << std::setw(10) << format_number(p.value, 6)
                      << p.expected() << "; " << p.meaning << "\n";
    }
    std::cout << "\nmethod kinds:\n";
    for (const auto& k : method_kinds()) std::cout << "    " << std::left << std::setw(10) << k.label << k.description << "\n";
    std::cout << "besides the catalog's tables (sympl tables) and a scene's own [[table]]s:";
    for (const auto& name : method_names_beside_tables()) std::cout << " " << name;
    std::cout << "\n";
}

void print_tables(bool json) {
    const auto& all = sympl::catalog();
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& t : all)
            out.push_back({{"name", t.name()},
                           {"family", t.family()},
                           {"order", t.order()},
                           {"stages", t.stages()},
                           {"force_evaluations", t.force_evaluations()},
                           {"symmetric", t.is_symmetric()},
                           {"needs_quadratic_T", t.needs_quadratic_kinetic()},
                           {"stability_interval", t.stability_interval()},
                           {"error_at_equal_cost", sympl::error_at_equal_cost(t)},
                           {"citation", t.citation()},
                           {"kick", as_doubles(t.kick())},
                           {"drift", as_doubles(t.drift())}});
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::cout << "sympl catalog: each step does, for k = 0..M-1, p += kick[k]*dt*force(q), then q += drift[k]*dt*velocity(p)\n\n";
    std::cout << std::left << std::setw(25) << "name" << std::setw(16) << "family" << std::right << std::setw(6) << "order"
              << std::setw(7) << "stages" << std::setw(7) << "forces" << std::setw(5) << "sym" << std::setw(7) << "T"
              << std::setw(10) << "stability" << std::setw(11) << "error@300" << "  citation\n";
    for (const auto& t : all)
        std::cout << std::left << std::setw(25) << t.name() << std::setw(16) << t.family() << std::right << std::setw(6)
                  << t.order() << std::setw(7) << t.stages() << std::setw(7) << t.force_evaluations() << std::setw(5)
                  << (t.is_symmetric() ? "yes" : "no") << std::setw(7) << (t.needs_quadratic_kinetic() ? "p^2/2" : "any")
                  << std::setw(10) << fixed(t.stability_interval(), 3) << std::setw(11)
                  << scientific(sympl::error_at_equal_cost(t), 1) << "  " << t.citation() << "\n";
    std::cout << "\n" << all.size() << " methods. forces: force evaluations per step (the last force is reused);"
              << " T: 'p^2/2' = the order holds only for quadratic kinetic energy;"
              << " stability: largest omega*dt stable on the harmonic oscillator;"
              << " error@300: max error on the pendulum (q0 = 1.2, p0 = 0.3) at t = 3 with 300 force evaluations"
              << " (to choose between methods: lower is better at equal cost).\n";
    // Named methods that are not kick-drift tables (not in --json, whose entries are).
    std::cout << "\nforce-gradient tables (kicks that add the force's derivative; systems with force_derivative or a "
                 "templated potential):\n";
    for (const auto& t : sympl::force_gradient_catalog())
        std::cout << "  " << std::left << std::setw(25) << t.name() << std::right << "order " << t.order() << ", "
                  << t.force_evaluations() << " forces and " << t.force_gradient_evaluations() << " force derivative"
                  << (t.force_gradient_evaluations() == 1 ? "" : "s") << " a step  " << t.citation() << "\n";
    std::cout << "\nprocessed methods (a kernel every step, its processor only where the state is looked at):\n";
    for (const auto& m : sympl::processed_catalog()) {
        std::size_t processor_kicks = 0;
        for (const auto& o : m.processor) processor_kicks += o.kind == sympl::substep::kick;
        std::cout << "  " << std::left << std::setw(25) << m.name << std::right << "effective order " << m.order << ", "
                  << m.kernel.force_evaluations() << " forces a step, processor " << processor_kicks << " kicks  "
                  << m.citation << "\n";
    }
}

// The exact order from the BCH series to degree 11 certifies orders up to 10.
constexpr int algebraic_degree = 11;

int check_table(const std::string& kick_text, const std::string& drift_text, const std::string& convention, bool json) {
    const auto kick = sympl::app::parse_coefficient_list(kick_text, "--kick");
    const auto drift = sympl::app::parse_coefficient_list(drift_text, "--drift");
    const sympl::table t = convention == "seed"          ? sympl::from_seed("user", kick, drift)
                           : convention == "drift-first" ? sympl::from_drift_first("user", drift, kick)
                                                         : sympl::table("user", kick, drift);
    const auto quadratic = sympl::measure_order(t, sympl::order_problem::pendulum);
    const auto general = sympl::measure_order(t, sympl::order_problem::nonquadratic_kinetic);
    const sympl::order_conditions_reading exact = sympl::read_order_conditions(t, algebraic_degree);
    const auto range = [](const sympl::order_measurement& m) {
        return nlohmann::json{{"largest_difference", m.largest_difference},
                              {"smallest_difference", m.smallest_difference},
                              {"agreeing_slopes", m.agreeing},
                              {"coefficient_rounding_below", m.rounding_level}};
    };
    if (json) {
        const nlohmann::json out = {{"stages", t.stages()},
                                    {"force_evaluations", t.force_evaluations()},
                                    {"symmetric", t.is_symmetric()},
                                    {"order", std::round(quadratic.order * 1000) / 1000},
                                    {"order_read", range(quadratic)},
                                    {"order_general", std::round(general.order * 1000) / 1000},
                                    {"order_general_read", range(general)},
                                    {"stability_interval", t.stability_interval()},
                                    {"error_at_equal_cost", sympl::error_at_equal_cost(t)},
                                    {"algebraic_order", exact.representable ? nlohmann::json(exact.general) : nlohmann::json()},
                                    {"algebraic_order_quadratic_T",
                                     exact.representable ? nlohmann::json(exact.quadratic) : nlohmann::json()},
                                    {"leading_error",
                                     exact.representable ? nlohmann::json(exact.leading_error) : nlohmann::json()},
                                    {"kick", as_doubles(t.kick())},
                                    {"drift", as_doubles(t.drift())}};
        std::cout << out.dump() << "\n";
        return 0;
    }
    const auto where = [](const sympl::order_measurement& m) {
        std::string w = "read where |x(dt) - x(dt/2)| fell from " + scientific(m.largest_difference, 1) + " to " +
                        scientific(m.smallest_difference, 1) + " (" + std::to_string(m.agreeing) + " slopes agreeing";
        if (m.rounding_level > 0)
            w += "; below " + scientific(m.rounding_level, 1) + " the rounding of the coefficients sets the slope";
        return w + ")";
    };
    std::cout << "canonical table (kick first):\n  kick  = " << nlohmann::json(as_doubles(t.kick())).dump()
              << "\n  drift = " << nlohmann::json(as_doubles(t.drift())).dump() << "\n"
              << "stages              " << t.stages() << "\n"
              << "force_evaluations   " << t.force_evaluations() << "\n"
              << "symmetric           " << (t.is_symmetric() ? "yes" : "no") << "\n"
              << "order               " << fixed(quadratic.order, 2) << "   pendulum, T = p^2/2; " << where(quadratic) << "\n"
              << "order_general       " << fixed(general.order, 2) << "   relativistic pendulum, T = sqrt(1+p^2); "
              << where(general) << "\n"
              << "algebraic_order     ";
    if (!exact.representable) {
        std::cout << "-      the coefficients overflow the series (magnitudes near the double range)\n";
    } else {
        const auto shown = [](int p) {
            return p == algebraic_degree ? std::to_string(p) + "+" : std::to_string(p);
        };
        std::cout << std::left << std::setw(7) << shown(exact.general) << std::right
                  << "exact, from the BCH series; T = p^2/2: " << shown(exact.quadratic);
        if (exact.general < algebraic_degree)
            std::cout << "; first unmet condition |E_" << exact.general + 1 << "| = "
                      << scientific(exact.leading_error, 2);
        std::cout << "\n";
    }
    std::cout << "stability_interval  " << fixed(t.stability_interval(), 4)
              << "   largest omega*dt stable on the harmonic oscillator\n"
              << "error_at_equal_cost " << scientific(sympl::error_at_equal_cost(t), 2)
              << "   pendulum at t = 3 with 300 force evaluations\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    sympl::app::handle_interrupts();  // first: before any other thread exists
    CLI::App app{"sympl: symplectic splitting methods for separable Hamiltonians H = T(p) + V(q)"};
    app.require_subcommand(1);

    auto* tables = app.add_subcommand("tables", "List every method of the catalog");
    bool tables_json = false;
    tables->add_flag("--json", tables_json, "JSON output");

    auto* systems = app.add_subcommand("systems", "List every system, its parameters and the method kinds");
    bool systems_json = false;
    systems->add_flag("--json", systems_json, "JSON output");

    auto* check = app.add_subcommand("check-table", "Validate a table and measure its order and stability");
    std::string kick, drift, convention = "kick-first";
    bool check_json = false;
    check->add_option("--kick", kick, "kick coefficients, comma-separated")->required();
    check->add_option("--drift", drift, "drift coefficients, comma-separated")->required();
    check->add_option("--convention", convention, "kick-first (default), drift-first, or seed (eq. 3.74: sums = M)")
        ->check(CLI::IsMember({"kick-first", "drift-first", "seed"}));
    check->add_flag("--json", check_json, "JSON output");

    auto* run = app.add_subcommand("run", "Run one scene file and print its summary");
    std::string scene_file;
    bool run_json = false;
    run->add_option("scene", scene_file, "scene file (TOML)")->required();
    run->add_flag("--json", run_json, "JSON output");
    double max_steps = sympl::app::default_max_steps;
    const auto max_steps_option = [&](CLI::App* command, double& target) {
        command->add_option("--max-steps", target, "refuse runs of more steps than this (default 1e9)")
            ->check(CLI::Range(1.0, 1e18));
    };
    max_steps_option(run, max_steps);
    bool resume = false;
    run->add_flag("--resume", resume, "continue from the scene's checkpoints (checkpoint = {every_steps, file})");

    auto* report = app.add_subcommand("report", "Work-precision study over scenes (default: the built-in set)");
    std::vector<std::string> report_files;
    sympl::app::report_options report_options;
    report->add_option("scenes", report_files, "scene files (TOML); none: the built-in set");
    report->add_option("--out", report_options.out_dir, "output directory (default sympl-report)");
    report->add_flag("--quick", report_options.quick, "short runs: under a minute on 2 cores");
    report->add_flag("--no-plots", [&](std::int64_t) { report_options.plots = false; }, "skip the gnuplot PNGs");
    max_steps_option(report, report_options.max_steps);

    auto* ensemble = app.add_subcommand("ensemble", "Run a scene's [ensemble] (grid or CSV of states): threads, MPI ranks");
    std::string ensemble_file, ensemble_out = "sympl-ensemble";
    int ensemble_threads = 0;
    double ensemble_max_steps = sympl::app::default_max_steps;
    ensemble->add_option("scene", ensemble_file, "scene file (TOML) with an [ensemble] table")->required();
    ensemble->add_option("--out", ensemble_out, "output directory (default sympl-ensemble)");
    ensemble->add_option("--threads", ensemble_threads, "threads per process (default: OMP_NUM_THREADS, else every core)")
        ->check(CLI::Range(1, 1024));
    max_steps_option(ensemble, ensemble_max_steps);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "sympl: " << e.what() << "\n";
        return 2;
    }
    sympl::app::exchange ranks;  // the MPI ranks of `ensemble` and `report` under mpirun
    // Under MPI an error on one rank ends them all (the others may wait for it in a gather).
    const auto fail = [&](const char* what) {
        const std::string who = ranks.size > 1 ? " (rank " + std::to_string(ranks.rank) + " of " +
                                                     std::to_string(ranks.size) + ")"
                                               : std::string();
        std::cerr << "sympl" << who << ": " << what << "\n";
        if (ranks.size > 1) ranks.abort_all(2);
        return 2;
    };
    try {
        if (*tables) print_tables(tables_json);
        if (*systems) print_systems(systems_json);
        if (*check) return check_table(kick, drift, convention, check_json);
        if (*ensemble || *report) ranks = sympl::app::process_exchange();
        if (*ensemble)
            sympl::app::ensemble_command(sympl::app::load_scene(ensemble_file), ensemble_out, ensemble_threads,
                                         ensemble_max_steps, ranks, std::cout);
        if (*run) sympl::app::run_scene(sympl::app::load_scene(scene_file), run_json, std::cout, max_steps, resume);
        if (*report) {
            std::vector<sympl::app::scene> scenes;
            for (const auto& f : report_files) scenes.push_back(sympl::app::load_scene(f, report_options.quick));
            report_options.studies = report_files.empty();
            if (scenes.empty()) scenes = sympl::app::default_scenes(report_options.quick);
            sympl::app::run_report(scenes, report_options, std::cout, ranks);
        }
    } catch (const sympl::error& e) {
        return fail(e.what());
    } catch (const std::filesystem::filesystem_error& e) {
        return fail(e.what());
    }
    return 0;
}
