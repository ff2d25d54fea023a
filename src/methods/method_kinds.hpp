#pragma once
// Every kind of method the program runs, one row each: its names in scenes
// (a family's members with their parameters: stages, pair, step control,
// Odeint stepper), what it needs of a system, whether a run can be
// checkpointed, how the report labels it. How a kind runs is its run_kind<K>
// in run_kinds.hpp, read by every system through the one dispatch there.
// Adding a kind is a row here plus its run_kind; adding a member to a family
// is a line in its members; adding a classic stepper is a line in
// classic_methods.
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <tuple>
#include <vector>

#include <sympl/core/table.hpp>
#include <sympl/methods/classic_steppers.hpp>
#include <sympl/methods/processing.hpp>

#include "methods/requirements.hpp"

namespace sympl {
struct wisdom_holman_options;  // planetary/wisdom_holman_plan.hpp
}

namespace sympl::app {

enum class method_kind {
    table, processed, logh, classic, odeint, gauss, tao, semiexplicit, dprkn, wisdom_holman, charged,
};
inline constexpr std::size_t method_kind_count = std::size_t(method_kind::charged) + 1;

// A set of method kinds, as a template argument: the kinds a system's
// registry entry compiles for its own type (runnable.hpp, systems/*.cpp).
struct kind_set {
    std::uint32_t bits = 0;
    constexpr kind_set() = default;
    constexpr kind_set(std::initializer_list<method_kind> kinds) {
        for (method_kind k : kinds) bits |= std::uint32_t(1) << unsigned(k);
    }
    constexpr bool has(method_kind k) const { return (bits >> unsigned(k)) & 1; }
    constexpr kind_set operator|(kind_set o) const { return from_bits(bits | o.bits); }
    static constexpr kind_set from_bits(std::uint32_t b) {
        kind_set s;
        s.bits = b;
        return s;
    }
};
inline constexpr kind_set all_kinds = kind_set::from_bits((std::uint32_t(1) << method_kind_count) - 1);

enum class step_control { fixed, controlled };  // controlled: swept over tolerances instead of step sizes
enum class odeint_stepper { rk4, dopri5, fehlberg78, bulirsch_stoer };
enum class rkn_pair { dprkn6, dprkn8, dprkn12 };
// charged: the pusher or splitting (sympl/charged/).
enum class charged_scheme { boris, relativistic, cartesian_split, cylindrical_split };

// What a named member of a family adds to its kind (the rest is the row's).
struct method_parameters {
    step_control control = step_control::fixed;
    int stages = 0;                                // gauss: s stages, order 2s
    rkn_pair pair = rkn_pair::dprkn6;              // dprkn
    odeint_stepper stepper = odeint_stepper::rk4;  // odeint
    charged_scheme scheme = charged_scheme::boris;  // charged
    friend constexpr bool operator==(const method_parameters&, const method_parameters&) = default;
};

// A scene name that is one method of a family, e.g. dprkn12_controlled.
struct named_method {
    const char* name;
    method_parameters parameters;
    const char* description;        // for listings
    bool symplectic = false;         // keeps the symplectic form on a Hamiltonian system (the energy figure)
    const char* not_resumable = "";  // why this member cannot resume bit for bit ("" when it can)
};

// One row per kind: what every method of the kind shares. Whether a method can
// resume from a checkpoint is read here only (why_not_resumable).
struct method_kind_entry {
    method_kind kind;
    const char* label;                     // the kind column of work_precision.csv
    std::span<const named_method> members = {};  // a family's scene names; empty for kinds named by a pattern
    bool fictitious_time = false;          // dt is LogH's fictitious step, not a step in physical time
    bool odeint = false;                   // a Boost.Odeint stepper (the report's competitors)
    needs requirement = needs::any;        // classic methods: per method, see classic_methods
    // Its methods keep the symplectic form on a Hamiltonian system, bar the
    // extrapolated ones; a family's members and the classic steppers say it
    // for themselves (symplectic(method_spec)).
    bool symplectic = false;
    const char* not_resumable = "";        // why no method of the kind can resume bit for bit ("" when they can)
    const char* controlled_not_resumable = "";    // why its step-size controlled members cannot
    const char* extrapolated_not_resumable = "";  // why its extrapolated(...) methods cannot
    const char* history_not_resumable = "";       // why its steppers with a history (classic_methods) cannot
    const char* description = "";          // for listings and error messages (kinds named by a pattern)
    // Runs on the generic path (generic_path.hpp) where a system's entry does
    // not compile it: its steppers need no more of a Hamiltonian than the
    // type-erased one offers (erased_system.hpp). Wisdom-Holman and the
    // charged pushers need masses or fields, and stay compiled where they apply.
    bool generic = false;
};

inline constexpr std::array odeint_members{
    named_method{"odeint_rk4", {.stepper = odeint_stepper::rk4}, "Boost.Odeint runge_kutta4, fixed step"},
    named_method{"odeint_dopri5", {.control = step_control::controlled, .stepper = odeint_stepper::dopri5},
                 "Boost.Odeint controlled runge_kutta_dopri5, absolute = relative tolerance"},
    named_method{"odeint_fehlberg78", {.control = step_control::controlled, .stepper = odeint_stepper::fehlberg78},
                 "Boost.Odeint controlled runge_kutta_fehlberg78, absolute = relative tolerance"},
    named_method{"odeint_bulirsch_stoer",
                 {.control = step_control::controlled, .stepper = odeint_stepper::bulirsch_stoer},
                 "Boost.Odeint bulirsch_stoer, absolute = relative tolerance"},
};

inline constexpr std::array gauss_members{
    named_method{.name = "gauss_2", .parameters = {.stages = 1},
                 .description = "implicit Gauss-Legendre collocation, s = 1 (the implicit midpoint rule), order 2: "
                                "symplectic for any H(q, p), separable or not",
                 .symplectic = true},
    named_method{.name = "gauss_4", .parameters = {.stages = 2},
                 .description = "implicit Gauss-Legendre collocation, s = 2, order 4, any H(q, p)", .symplectic = true},
    named_method{.name = "gauss_6", .parameters = {.stages = 3},
                 .description = "implicit Gauss-Legendre collocation, s = 3, order 6, any H(q, p)", .symplectic = true},
    named_method{.name = "gauss_8", .parameters = {.stages = 4},
                 .description = "implicit Gauss-Legendre collocation, s = 4, order 8, any H(q, p)", .symplectic = true},
    named_method{.name = "gauss_10", .parameters = {.stages = 5},
                 .description = "implicit Gauss-Legendre collocation, s = 5, order 10, any H(q, p)", .symplectic = true},
    named_method{.name = "gauss_12", .parameters = {.stages = 6},
                 .description = "implicit Gauss-Legendre collocation, s = 6, order 12, any H(q, p)", .symplectic = true},
};

inline constexpr std::array dprkn_members{
    named_method{"dprkn6", {.pair = rkn_pair::dprkn6},
                 "not symplectic: Dormand-Prince RKN6(4) pair, fixed step (the order-6 result)"},
    named_method{"dprkn8", {.pair = rkn_pair::dprkn8},
                 "not symplectic: Dormand-El-Mikkawy-Prince RKN8(6) pair, fixed step"},
    named_method{"dprkn12", {.pair = rkn_pair::dprkn12},
                 "not symplectic: Dormand-El-Mikkawy-Prince RKN12(10) pair, fixed step"},
    named_method{"dprkn6_controlled", {.control = step_control::controlled, .pair = rkn_pair::dprkn6},
                 "not symplectic: dprkn6 with its step size controlled, absolute = relative tolerance"},
    named_method{"dprkn8_controlled", {.control = step_control::controlled, .pair = rkn_pair::dprkn8},
                 "not symplectic: dprkn8 with its step size controlled, absolute = relative tolerance"},
    named_method{"dprkn12_controlled", {.control = step_control::controlled, .pair = rkn_pair::dprkn12},
                 "not symplectic: dprkn12 with its step size controlled, absolute = relative tolerance"},
};

inline constexpr std::array charged_members{
    named_method{"boris", {.scheme = charged_scheme::boris},
                 "Boris pusher (Boris 1970), drift-kick-drift: explicit, order 2, volume-preserving, not symplectic; "
                 "Newton's motion only"},
    named_method{"boris(relativistic = true)", {.scheme = charged_scheme::relativistic},
                 "relativistic pusher of Higuera & Cary (2017), drift-kick-drift: explicit, order 2, volume-preserving, "
                 "not symplectic; Boris's at |v| << c"},
};

// The registry, in the order of method_kind.
inline constexpr std::array<method_kind_entry, method_kind_count> method_kind_entries{{
    {.kind = method_kind::table, .label = "table", .requirement = needs::splitting, .symplectic = true,
     .description = "a splitting table: the catalog's (sympl tables) or a scene's own [[table]], on a separable "
                    "Hamiltonian or, with exact damped drifts, on a damped, driven system; extrapolated(<symmetric "
                    "table>, k) extrapolates it over k runs of 1..k steps (order p + 2(k - 1)); compensated(<table>) sums "
                    "the updates with Kahan's compensation (both on separable Hamiltonians); a force-gradient table "
                    "(chin_4a, ...) also needs the force's derivative", .generic = true},
    {.kind = method_kind::processed, .label = "processed", .requirement = needs::separable_hamiltonian,
     .symplectic = true,
     .description = "a processed method (blanes_2001_p6, ...): a kernel every step, its processor only where the state is "
                    "looked at; every output is the true state", .generic = true},
    {.kind = method_kind::logh, .label = "logh", .fictitious_time = true, .requirement = needs::negative_potential,
     .symplectic = true,
     .description = "logh(<table>): the table in LogH fictitious time (Mikkola & Tanikawa 1999); dt is the fictitious "
                    "step; extrapolated(logh(<symmetric table>), k) as above", .generic = true},
    {.kind = method_kind::classic, .label = "classic",
     .description = "a classic stepper of Gould & Tobochnik or Sandvik", .generic = true},
    {.kind = method_kind::odeint, .label = "odeint", .members = odeint_members, .odeint = true, .generic = true},
    {.kind = method_kind::gauss, .label = "gauss", .members = gauss_members, .requirement = needs::general_hamiltonian,
     .symplectic = true, .generic = true},
    {.kind = method_kind::tao, .label = "tao", .requirement = needs::general_hamiltonian, .symplectic = true,
     .description = "tao(<table>[, omega = W]): Tao's explicit method for any H(q, p) (extended phase space; the "
                    "binding omega unless given 4 times the fastest frequency at the start, in each component's units), "
                    "composed by a symmetric composition of leapfrog steps (leapfrog_kdk, yoshida_4, yoshida_6, ...); "
                    "symplectic in the extended space only", .generic = true},
    {.kind = method_kind::semiexplicit, .label = "semiexplicit", .requirement = needs::general_hamiltonian,
     .symplectic = true,
     .description = "semiexplicit(<table>): Jayawardana & Ohsawa's semiexplicit method for any H(q, p), composed "
                    "by a symmetric composition of leapfrog steps; symplectic and symmetric", .generic = true},
    {.kind = method_kind::dprkn, .label = "rkn_nonsymplectic", .members = dprkn_members,
     .requirement = needs::quadratic_kinetic, .generic = true},
    {.kind = method_kind::wisdom_holman, .label = "wisdom_holman", .requirement = needs::planetary, .symplectic = true,
     .description = "wh(<table>[, corrector = K][, kernel = composition|lazy][, coordinates = jacobi]): "
                    "Wisdom-Holman splitting of a planetary system, the table's drifts the exact Kepler flow about "
                    "the star (Jacobi: about the interior masses), its kicks the planets' interaction "
                    "(planetary/wisdom_holman_stepper.hpp); leapfrog_kdk, saba_2, ... (tables for T = p^2/2 lose their extra order "
                    "here); a symmetric table takes a symplectic corrector of order K = 3, 5, 7, 9, 11 or 17, "
                    "leapfrog_dkd a kernel too (lazy: Jacobi coordinates only)"},
    {.kind = method_kind::charged, .label = "charged", .members = charged_members,
     .requirement = needs::charged_particle, .symplectic = true,  // the splittings; not its members, the pushers
     .description = "boris, boris(relativistic = true), cartesian_split(<table>), cylindrical_split(<table>): a charged "
                    "particle's pushers and explicit symplectic splittings (sympl/charged/); cartesian_split composes "
                    "the exactly solvable parts (p_i - e A_i)^2/2m by a symmetric composition of leapfrog steps "
                    "(yoshida_6, kahan_li_8, ...), cylindrical_split runs any kick-drift table (blanes_moan_srkn11b, "
                    "...) in cylindrical coordinates for a field symmetric about z; both symplectic, Newton's motion "
                    "only"},
}};

constexpr const method_kind_entry& entry_of(method_kind kind) { return method_kind_entries[std::size_t(kind)]; }
const std::array<method_kind_entry, method_kind_count>& method_kinds();

// Whether some method of the kind can resume from a checkpoint: the row's
// answer before any parameter, which decides whether the checkpointed driver
// is compiled for the kind (run_kinds.hpp).
constexpr bool kind_may_resume(method_kind kind) { return *entry_of(kind).not_resumable == '\0'; }

// The kinds the generic path runs (their rows' `generic`).
constexpr kind_set generic_kinds() {
    kind_set s;
    for (const method_kind_entry& e : method_kind_entries)
        if (e.generic) s = s | kind_set{e.kind};
    return s;
}

// A classic stepper of classic_steppers.hpp under its scene name.
template <template <class, class> class Stepper, needs Needs>
struct classic_method {
    const char* name;
    const char* description;
    // Carries a history between steps (a half-step momentum, the previous
    // position): a checkpoint holds it as the stepper's carried list.
    bool history = false;
    bool symplectic = false;  // on a separable Hamiltonian (docs/classic.md)
    static constexpr needs requirement = Needs;
};

// The classic steppers, by name; a method_spec of kind classic holds its index here.
inline constexpr std::tuple classic_methods{
    classic_method<euler, needs::any>{"euler", "Euler, first order"},
    classic_method<euler_cromer, needs::any>{.name = "euler_cromer",
                                             .description = "Euler-Cromer (Gould & Tobochnik), first order, symplectic",
                                             .symplectic = true},
    classic_method<half_step, needs::any>{.name = "half_step",
                                          .description = "half-step algorithm (Gould & Tobochnik eq. 3.37)",
                                          .history = true, .symplectic = true},
    classic_method<euler_richardson, needs::any>{"euler_richardson", "Euler-Richardson (Gould & Tobochnik eqs. 3.43-3.44)"},
    classic_method<rk2, needs::any>{"rk2", "midpoint Runge-Kutta (Sandvik's lecture notes) = euler_richardson"},
    classic_method<rk4, needs::any>{"rk4", "classic fourth-order Runge-Kutta (Sandvik's lecture notes)"},
    classic_method<velocity_verlet, needs::any>{.name = "velocity_verlet",
                                                .description = "velocity Verlet (Gould & Tobochnik eq. 3.48)",
                                                .history = true, .symplectic = true},
    classic_method<leapfrog_two_step, needs::newtonian>{.name = "leapfrog_two_step",
                                                        .description = "two-step leapfrog (Gould & Tobochnik eq. 3.47)",
                                                        .history = true, .symplectic = true},
    classic_method<damped_leapfrog, needs::damped_split>{"damped_leapfrog",
                                                         "leapfrog with velocity-dependent damping (Sandvik)", true},
    classic_method<predictor_corrector, needs::any>{"predictor_corrector",
                                                    "predictor-corrector (Gould & Tobochnik eqs. 3.69-3.70)", true},
};
inline constexpr std::size_t classic_method_count = std::tuple_size_v<decltype(classic_methods)>;

// Classic steppers by index in classic_methods, as a template argument: those
// a system's registry entry compiles for its own type, named as in scenes
// (an unknown name does not compile).
struct classic_set {
    std::uint32_t bits = 0;
    constexpr classic_set() = default;
    constexpr classic_set(std::initializer_list<std::string_view> names) {
        for (std::string_view name : names) bits |= std::uint32_t(1) << index_of(name);
    }
    constexpr bool has(std::size_t index) const { return (bits >> index) & 1; }
    static constexpr std::size_t index_of(std::string_view name) {
        std::size_t found = classic_method_count;
        [&]<std::size_t... I>(std::index_sequence<I...>) {
            ((std::string_view(std::get<I>(classic_methods).name) == name ? void(found = I) : void()), ...);
        }(std::make_index_sequence<classic_method_count>{});
        if (found == classic_method_count) throw std::invalid_argument("not a classic stepper's name");
        return found;
    }
};
inline constexpr classic_set all_classic = [] {
    classic_set s;
    s.bits = (std::uint32_t(1) << classic_method_count) - 1;
    return s;
}();

// The methods compiled for a system's own type: its kinds and, of the classic
// kind, its steppers (runnable.hpp).
struct compiled_methods {
    kind_set kinds = all_kinds;
    classic_set classic = all_classic;
    bool extrapolated = true;  // the table and LogH kinds' extrapolated(...) variants
    constexpr bool has(const method_kind kind, std::size_t classic_index) const {
        return kinds.has(kind) && (kind != method_kind::classic || classic.has(classic_index));
    }
};

// What any classic method is, by index, without its stepper type.
struct classic_facts {
    const char* name;
    needs requirement;
    bool history;
    bool symplectic;
};
classic_facts classic_at(std::size_t index);

struct method_spec {
    std::string name;
    method_kind kind = method_kind::table;
    std::optional<table> coefficients;  // for kind == table (force-gradient tables too), logh, tao, semiexplicit, wh
    std::optional<processed_method> processing = std::nullopt;  // for kind == processed
    int extrapolation_columns = 0;      // extrapolated(<table or logh(table)>, k): k > 0
    bool compensated = false;           // compensated(<table>): Kahan-summed updates
    std::size_t classic = 0;            // for kind == classic: the index in classic_methods
    method_parameters parameters;       // for a family's member (odeint, gauss, dprkn): its row in members
    // wh(<table>, corrector = K, kernel = composition|lazy, coordinates = jacobi): wisdom_holman_options.
    int corrector_order = 0;            // 0: none
    bool composition_kernel = false;
    bool lazy_kernel = false;           // Jacobi coordinates only
    bool jacobi = false;                // wh(..., coordinates = jacobi)
    // charged: cartesian_split(<table>) and cylindrical_split(<table>) set parameters.scheme and coefficients.
    std::optional<double> omega;        // tao(<table>, omega = W); unset: from the problem's scales
};

// Whether a method runs on what is compiled: its kind, its classic stepper,
// its extrapolation.
constexpr bool compiled_has(const compiled_methods& c, const method_spec& m) {
    return c.has(m.kind, m.classic) && (m.extrapolation_columns == 0 || c.extrapolated);
}

// Whether the method is swept over tolerances (its step size controlled)
// instead of step sizes.
inline bool adaptive(const method_spec& m) { return m.parameters.control == step_control::controlled; }

// Whether the method's dt is a step in physical time (not a tolerance, and not
// LogH's fictitious step).
inline bool steps_in_physical_time(const method_spec& m) { return !adaptive(m) && !entry_of(m.kind).fictitious_time; }

// The names a scene may give beside the catalog's and its own [[table]]s
// (and logh(<table>)): the classic steppers, the Odeint kinds, the
// force-gradient tables and the processed methods.
std::vector<std::string> method_names_beside_tables();

// The method a scene names: an inline table first, then a kind that is one
// method (Odeint, Gauss-Legendre, RKN pairs), a classic stepper, a catalog
// table, a force-gradient table, a processed method, and logh(<any of the
// plain tables>) for the table run in LogH fictitious time,
// extrapolated(<table or logh(table)>, k), tao(<table>) and
// semiexplicit(<table>) for a symmetric composition of leapfrog steps run on
// any H(q, p), wh(<table>) for the table's Wisdom-Holman splitting of a
// planetary system; nullopt when the name is none of these. A malformed
// extrapolated(...), logh(...), tao(...), semiexplicit(...) or wh(...) is an
// invalid_argument that says what is wrong.
inline constexpr int max_extrapolation_columns = 12;
// How deep a method name's calls may nest (extrapolated(logh(leapfrog_dkd), 6)
// nests 2 deep): a deeper name is refused before any of it is resolved, so
// that resolving is a bounded recursion whatever a scene holds.
inline constexpr int max_method_nesting = 8;
std::optional<method_spec> resolve_method(const std::string& name, const std::map<std::string, table>& inline_tables);

// "did you mean 'logh(leapfrog_dkd)'? " for a pattern around an unknown
// table (logh(...), compensated(...)) that resolve_method returned nothing
// for, or "" (the other patterns name their nearest table in their error).
std::string did_you_mean_method(const std::string& name, const std::map<std::string, table>& inline_tables);

// The library's options for a wh(...) method: its corrector, kernel and
// coordinates (the one place that maps them; the scene's check and the run
// both ask it).
wisdom_holman_options wisdom_holman_options_of(const method_spec& m);

// Why a checkpointed run of `m` could not be resumed bit for bit ("" when it
// can): tables (force-gradient ones too), plain or compensated, and the
// classic steppers without history.
std::string why_not_resumable(const method_spec& m);

// Whether `m` keeps the symplectic form on a Hamiltonian system (the energy
// figure draws the fastest symplectic method against the fastest other one):
// its member's or classic stepper's flag, else its kind's; never an
// extrapolated method (a combination of runs of different step counts).
bool symplectic(const method_spec& m);

// What `m` needs of a system.
needs requirement_of(const method_spec& m);

// Why `m` cannot run on a system of `form` ("" when it can): "method 'x' ...".
std::string why_not(const method_spec& m, const system_form& form);

}  // namespace sympl::app
