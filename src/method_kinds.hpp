#pragma once
// Every kind of method the program runs, in one place: how a name in a scene
// resolves, what each kind needs of a system, and why it cannot run where it
// cannot. Adding a classic stepper is adding a line to classic_methods;
// adding a kind is adding an entry to method_kinds() and a case to the runner.
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <sympl/classic_steppers.hpp>
#include <sympl/processing.hpp>
#include <sympl/table.hpp>

namespace sympl::app {

enum class method_kind { table, processed, logh, classic, odeint_rk4, odeint_dopri5, odeint_fehlberg78, odeint_bulirsch_stoer };

struct method_spec {
    std::string name;
    method_kind kind = method_kind::table;
    std::optional<table> coefficients;  // for kind == table (force-gradient tables too) and logh
    std::optional<processed_method> processing = std::nullopt;  // for kind == processed
    int extrapolation_columns = 0;      // extrapolated(<table or logh(table)>, k): k > 0
    bool compensated = false;           // compensated(<table>): Kahan-summed updates
};

// What a system's equations offer a method.
struct system_form {
    bool separable_hamiltonian = false;  // H = T(p) + V(q): what a splitting table needs
    bool newtonian = false;              // x'' = a(x, v, t), q = x and p = v
    bool damped_split = false;           // a force split as F(x, t) - G(v)
    bool negative_potential = false;     // V(q) < 0 everywhere (gravitation): what LogH needs
    bool differentiable_force = false;   // J_F(q) u, analytic or by dual numbers: what force-gradient kicks need
};

enum class needs { any, separable_hamiltonian, newtonian, damped_split, negative_potential, differentiable_force };

// Why a method that needs `n` cannot run on a system of `form` ("" when it can).
std::string why_not(needs n, const system_form& form);

struct method_kind_entry {
    method_kind kind;
    const char* label;        // the kind column of work_precision.csv
    bool adaptive;            // swept over tolerances instead of step sizes
    bool odeint;              // a Boost.Odeint stepper (the report's competitors)
    needs requirement;        // for classic methods: per method, see classic_methods
    const char* description;  // for listings and error messages
};
const std::vector<method_kind_entry>& method_kinds();
const method_kind_entry& entry_of(method_kind kind);

// Whether the method's dt is a step in physical time (not a tolerance, and not
// LogH's fictitious step).
inline bool steps_in_physical_time(const method_spec& m) {
    return !entry_of(m.kind).adaptive && m.kind != method_kind::logh;
}

// A classic stepper of classic_steppers.hpp under its scene name.
template <template <class, class> class Stepper, needs Needs>
struct classic_method {
    const char* name;
    const char* description;
    // Carries a history between steps (a half-step momentum, the previous
    // position): a checkpoint of the state alone cannot resume it bit for bit.
    bool history = false;
    static constexpr needs requirement = Needs;
};

// The classic steppers, by name; the runner instantiates each on every system
// whose form meets its requirement.
inline constexpr std::tuple classic_methods{
    classic_method<euler, needs::any>{"euler", "Euler, first order"},
    classic_method<euler_cromer, needs::any>{"euler_cromer", "Euler-Cromer (Gould & Tobochnik), first order, symplectic"},
    classic_method<half_step, needs::any>{"half_step", "half-step algorithm (Gould & Tobochnik eq. 3.37)", true},
    classic_method<euler_richardson, needs::any>{"euler_richardson", "Euler-Richardson (Gould & Tobochnik eqs. 3.43-3.44)"},
    classic_method<rk2, needs::any>{"rk2", "midpoint Runge-Kutta (Sandvik's lecture notes) = euler_richardson"},
    classic_method<rk4, needs::any>{"rk4", "classic fourth-order Runge-Kutta (Sandvik's lecture notes)"},
    classic_method<velocity_verlet, needs::any>{"velocity_verlet", "velocity Verlet (Gould & Tobochnik eq. 3.48)", true},
    classic_method<leapfrog_two_step, needs::newtonian>{"leapfrog_two_step",
                                                        "two-step leapfrog (Gould & Tobochnik eq. 3.47)", true},
    classic_method<damped_leapfrog, needs::damped_split>{"damped_leapfrog",
                                                         "leapfrog with velocity-dependent damping (Sandvik)", true},
    classic_method<predictor_corrector, needs::any>{"predictor_corrector",
                                                    "predictor-corrector (Gould & Tobochnik eqs. 3.69-3.70)", true},
};

// The names a scene may give beside the catalog's and its own [[table]]s
// (and logh(<table>)): the classic steppers, the Odeint kinds, the
// force-gradient tables and the processed methods.
std::vector<std::string> method_names_beside_tables();

// The method a scene names: an inline table first, then an Odeint kind, a
// classic stepper, a catalog table, a force-gradient table, a processed
// method, and logh(<any of the plain tables>) for the table run in LogH
// fictitious time, and extrapolated(<table or logh(table)>, k); nullopt when
// the name is none of these. A malformed extrapolated(...) or logh(...) is an
// invalid_argument that says what is wrong.
inline constexpr int max_extrapolation_columns = 12;
std::optional<method_spec> resolve_method(const std::string& name, const std::map<std::string, table>& inline_tables);

// Why a checkpointed run of `m` could not be resumed bit for bit ("" when it
// can): tables (force-gradient ones too), plain or compensated, and the
// classic steppers without history.
std::string why_not_resumable(const method_spec& m);

// What `m` needs of a system.
needs requirement_of(const method_spec& m);

// Why `m` cannot run on a system of `form` ("" when it can): "method 'x' ...".
std::string why_not(const method_spec& m, const system_form& form);

}  // namespace sympl::app
