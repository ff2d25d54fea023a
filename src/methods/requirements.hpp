#pragma once
// What a method needs of a system: one row per requirement, each with why a
// system of a given form does not meet it ("" when it does). The run-time
// answer (a scene's methods against its system) and the compile-time one
// (which kinds a system type is compiled for, run_context.hpp) both read the
// row, so a new requirement is a value of `needs` and its row; one that asks
// for a new property of systems adds that property to system_form and to
// form_of<Sys> (run_context.hpp).
#include <array>
#include <stdexcept>
#include <string>

namespace sympl::app {

// What a system's equations offer a method.
struct system_form {
    bool separable_hamiltonian = false;  // H = T(p) + V(q): what a splitting table needs
    bool newtonian = false;              // x'' = a(x, v, t), q = x and p = v
    bool damped_split = false;           // a force split as F(x, t) - G(v)
    bool negative_potential = false;     // V(q) < 0 everywhere (gravitation): what LogH needs
    bool differentiable_force = false;   // J_F(q) u, analytic or by dual numbers: what force-gradient kicks need
    bool conformal = false;              // dp/dt = F(q, t) - gamma p with dq/dt linear in p: damped tables
    bool general_hamiltonian = false;    // any H(q, p), separable or not: Gauss-Legendre, Tao, semiexplicit
    bool quadratic_kinetic = false;      // separable with T quadratic in p (dq/dt linear in p): the RKN pairs
    bool planetary = false;              // a star and planets with masses and G: Wisdom-Holman splitting
    bool charged = false;                // a charged particle in a field (particle(), electromagnetic_field()): sympl/charged/
};

enum class needs {
    any,
    separable_hamiltonian,
    newtonian,
    damped_split,
    negative_potential,
    differentiable_force,
    splitting,            // a kick-drift table: a separable Hamiltonian, or a damped, driven one (conformal_splitting.hpp)
    general_hamiltonian,  // any H(q, p) (general_hamiltonian.hpp), a separable one too
    quadratic_kinetic,    // a separable Hamiltonian whose T is quadratic in p: q'' = F(q) (rkn_pairs.hpp)
    planetary,            // point masses about a star, with `mass` (star first) and `G` (planetary/wisdom_holman_stepper.hpp)
    charged_particle,     // a charged particle with particle() and electromagnetic_field() (charged/particle.hpp, charged/fields.hpp)
};

struct requirement {
    needs n;
    const char* (*why_not)(const system_form&);  // "" when the form meets it
};

namespace detail {
constexpr const char* not_separable(const system_form& f) {
    if (f.separable_hamiltonian) return "";
    return f.general_hamiltonian ? "needs a separable Hamiltonian H = T(p) + V(q); this system's H(q, p) does not split "
                                   "(use gauss_4, gauss_6, semiexplicit(<table>) or tao(<table>))"
                                 : "needs a separable Hamiltonian H = T(p) + V(q); this system is not Hamiltonian (use a "
                                   "classic method)";
}
}  // namespace detail

// The rows, in any order (requirement_row finds them).
inline constexpr std::array requirements{
    requirement{needs::any, [](const system_form&) -> const char* { return ""; }},
    requirement{needs::separable_hamiltonian, detail::not_separable},
    requirement{needs::general_hamiltonian,
                [](const system_form& f) -> const char* {
                    return f.general_hamiltonian || f.separable_hamiltonian
                               ? ""
                               : "needs a Hamiltonian H(q, p); this system is not Hamiltonian (use a classic method)";
                }},
    requirement{needs::quadratic_kinetic,
                [](const system_form& f) -> const char* {
                    if (!f.separable_hamiltonian) return detail::not_separable(f);
                    return f.quadratic_kinetic ? ""
                                               : "needs a kinetic energy quadratic in p (the Runge-Kutta-Nystrom form "
                                                 "q'' = F(q)); this system's is not (use a table)";
                }},
    requirement{needs::newtonian,
                [](const system_form& f) -> const char* {
                    return f.newtonian ? ""
                                       : "needs Newton's form x'' = a(x, v, t); this system is Hamiltonian (use "
                                         "velocity_verlet)";
                }},
    requirement{needs::splitting,
                [](const system_form& f) -> const char* {
                    if (f.separable_hamiltonian || f.conformal) return "";
                    return f.general_hamiltonian
                               ? "needs a separable Hamiltonian H = T(p) + V(q) or a damped, driven one (dp/dt = F(q, "
                                 "t) - gamma p); this system's H(q, p) does not split (use gauss_4, gauss_6, "
                                 "semiexplicit(<table>) or tao(<table>))"
                               : "needs a separable Hamiltonian H = T(p) + V(q) or a damped, driven one (dp/dt = F(q, "
                                 "t) - gamma p); this system is neither (use a classic method)";
                }},
    requirement{needs::damped_split,
                [](const system_form& f) -> const char* {
                    return f.damped_split ? ""
                                          : "needs a force split as F(x, t) - G(v); only damped_oscillator has one";
                }},
    requirement{needs::differentiable_force,
                [](const system_form& f) -> const char* {
                    if (!f.separable_hamiltonian) return detail::not_separable(f);
                    return f.differentiable_force
                               ? ""
                               : "needs the force's derivative J_F(q) u (force-gradient kicks); this system gives "
                                 "neither force_derivative nor a potential templated on its scalar (use a table "
                                 "without force-gradient kicks)";
                }},
    requirement{needs::negative_potential,
                [](const system_form& f) -> const char* {
                    if (!f.separable_hamiltonian) return detail::not_separable(f);
                    return f.negative_potential ? ""
                                                : "needs V(q) < 0 everywhere (the LogH time transformation divides by "
                                                  "-V); this system's potential is not negative (use the table itself)";
                }},
    requirement{needs::planetary,
                [](const system_form& f) -> const char* {
                    return f.planetary ? ""
                                       : "needs a planetary system (a star and planets with masses and G; "
                                         "outer_solar_system); this system is not one (use the table itself)";
                }},
    requirement{needs::charged_particle,
                [](const system_form& f) -> const char* {
                    return f.charged ? ""
                                     : "needs a charged particle in an electromagnetic field (charged_particle, "
                                       "charged_uniform); this system is not one";
                }},
};

constexpr const requirement& requirement_row(needs n) {
    for (const requirement& r : requirements)
        if (r.n == n) return r;
    throw std::logic_error("a value of `needs` without its row in `requirements`");
}

// Why a method that needs `n` cannot run on a system of `form` ("" when it can).
inline std::string why_not(needs n, const system_form& form) { return requirement_row(n).why_not(form); }

}  // namespace sympl::app
