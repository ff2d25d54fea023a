// The systems the program knows: one entry each (see systems.hpp).
#include "systems.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <sympl/hamiltonians/damped_driven_oscillator.hpp>
#include <sympl/hamiltonians/double_well.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/morse.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>
#include <sympl/hamiltonians/stiff_fpu.hpp>
#include <sympl/hamiltonians/toda.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

#include "format.hpp"
#include "runner.hpp"

namespace sympl::app {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double largest_chain = 1e6;  // degrees of freedom: 16 MB per state, a run needs a few

// Parameter kinds, by their ranges.
parameter positive(std::string name, double value, std::string meaning) {
    return {std::move(name), value, 0, inf, true, false, false, std::move(meaning)};
}
parameter nonnegative(std::string name, double value, std::string meaning) {
    return {std::move(name), value, 0, inf, false, false, false, std::move(meaning)};
}
parameter any(std::string name, double value, std::string meaning) {
    return {std::move(name), value, -inf, inf, false, false, false, std::move(meaning)};
}
parameter count(std::string name, double value, double low, std::string meaning) {
    return {std::move(name), value, low, largest_chain, false, false, true, std::move(meaning)};
}

parameter of_initial_state(parameter p) {
    p.initial_state = true;
    return p;
}

using V1 = Eigen::Matrix<double, 1, 1>;
using S1 = phase_space<double, 1>;

// The exact flow x(t) = h.exact(x0, t) of a system that has one, as stacked vectors.
template <class H, class X>
std::function<std::vector<double>(double)> exact_flow(H h, X x0) {
    return [h, x0](double t) { return stacked(h.exact(x0, t)); };
}

const std::vector<system_entry>& registry() {
    static const std::vector<system_entry> entries = {
        {"harmonic_oscillator", "H = p^2/(2m) + m omega^2 q^2/2 (Sandvik's lecture notes); q0 = 1, p0 = 0",
         {positive("mass", 1, "m"), positive("omega", 1, "angular frequency")}, true,
         [](const parameter_values& v) {
             const hamiltonians::harmonic_oscillator h{v.at("mass"), v.at("omega")};
             const S1 x0(V1(1.0), V1(0.0));
             return model<1>(h, stacked(x0), exact_flow(h, x0));
         }},
        {"pendulum", "H = p^2/(2 m l^2) + m g l (1 - cos q); q0 = 1.2, p0 = 0.3",
         {positive("mass", 1, "m"), positive("length", 1, "l"), positive("gravity", 1, "g")}, false,
         [](const parameter_values& v) {
             return model<1>(hamiltonians::pendulum{v.at("mass"), v.at("length"), v.at("gravity")}, {1.2, 0.3});
         }},
        {"kepler",
         "H = |p|^2/2 - mu/|q| (Hairer, Lubich & Wanner, GNI ch. I.2.3), plane orbit from pericentre; exact for mu = 1",
         {positive("mu", 1, "G M; give mu or scale, not both"),
          of_initial_state({"eccentricity", 0.5, 0, 1, false, true, false, "orbit eccentricity e"}),
          positive("scale", 1, "length unit L: q -> L q, p -> L p, mu -> mu L^3 (the same orbit in other units)")},
         true,
         [](const parameter_values& v) {
             const double e = v.at("eccentricity"), L = v.at("scale"), mu = v.at("mu");
             if (mu != 1 && L != 1)
                 throw invalid_argument("kepler: mu = " + shortest(mu) + " and scale = " +
                                        shortest(L) + "; expected one of them left at 1");
             const auto scaled = [L](std::vector<double> x) {
                 for (double& c : x) c *= L;
                 return x;
             };
             std::function<std::vector<double>(double)> exact;
             if (mu == 1)
                 exact = [e, scaled](double t) { return scaled(stacked(hamiltonians::kepler::exact_state(e, t))); };
             return model<2>(hamiltonians::kepler{mu * L * L * L}, scaled(stacked(hamiltonians::kepler::initial_state(e))),
                          exact);
         },
         true},
        {"kepler_3d", "the Kepler orbit turned into space by the classical angles (mu = 1); exact",
         {of_initial_state({"eccentricity", 0.5, 0, 1, false, true, false, "orbit eccentricity e"}),
          of_initial_state(any("inclination", 0.3, "rad")),
          of_initial_state(any("node", 0.5, "longitude of the ascending node, rad")),
          of_initial_state(any("periapsis", 0.7, "argument of pericentre, rad"))},
         true,
         [](const parameter_values& v) {
             const double e = v.at("eccentricity"), i = v.at("inclination"), o = v.at("node"), w = v.at("periapsis");
             return model<3>(hamiltonians::kepler{}, stacked(hamiltonians::kepler::initial_state_3d(e, i, o, w)),
                          [=](double t) { return stacked(hamiltonians::kepler::exact_state_3d(e, i, o, w, t)); });
         },
         true},
        {"relativistic_pendulum", "H = m c^2 sqrt(1 + p^2/(m c)^2) + k (1 - cos q): a non-quadratic T; q0 = 1.2, p0 = 0.9",
         {positive("mass", 1, "m"), positive("c", 1, "speed of light"), positive("k", 1, "restoring torque")}, false,
         [](const parameter_values& v) {
             return model<1>(hamiltonians::relativistic_pendulum{v.at("mass"), v.at("c"), v.at("k")}, {1.2, 0.9});
         }},
        {"henon_heiles", "Henon & Heiles 1964; started on the surface of section q1 = 0 at the given energy",
         {of_initial_state({"energy", 1.0 / 6, 0, 1.0 / 6, true, false, false, "H; bounded motion up to 1/6"}),
          of_initial_state(any("q2", 0.1, "starting q2")), of_initial_state(any("p2", 0, "starting p2"))},
         false,
         [](const parameter_values& v) {
             return model<2>(hamiltonians::henon_heiles{},
                          stacked(hamiltonians::henon_heiles::initial_state(v.at("energy"), v.at("q2"), v.at("p2"))));
         }},
        {"fpu_beta", "Fermi, Pasta & Ulam 1955 beta chain, fixed ends; started in its lowest mode, amplitude 1",
         {count("n", 32, 1, "number of masses"), nonnegative("beta", 1, "quartic coupling")}, false,
         [](const parameter_values& v) {
             const auto n = std::size_t(v.at("n"));
             std::vector<double> x0(2 * n, 0.0);
             const double pi = std::acos(-1.0);
             for (std::size_t k = 0; k < n; ++k) x0[k] = std::sin(pi * double(k + 1) / double(n + 1));
             return model(hamiltonians::fpu_beta{v.at("beta")}, x0);
         }},
        {"stiff_fpu", "stiff Fermi-Pasta-Ulam problem (Hairer, Lubich & Wanner, GNI ch. I.5.1) with its initial data",
         {positive("omega", 50, "stiff springs' frequency"), count("pairs", 3, 1, "number of stiff pairs m")}, false,
         [](const parameter_values& v) {
             const hamiltonians::stiff_fpu h{v.at("omega")};
             return model(h, stacked(h.initial_state<double, Eigen::Dynamic>(int(v.at("pairs")))));
         }},
        {"outer_solar_system", "Sun and the five outer planets (Hairer, Lubich & Wanner, GNI Table 2.2); days, AU", {},
         false,
         [](const parameter_values&) {
             const hamiltonians::outer_solar_system h{};
             return model<hamiltonians::outer_solar_system::dimension>(h, stacked(h.initial_state()));
         },
         true},
        {"two_particle_spring", "two particles joined by a spring (Gould & Tobochnik eq. 3.72); exact",
         {positive("mass", 1, "each particle's mass"), positive("stiffness", 1, "spring constant k")}, true,
         [](const parameter_values& v) {
             const hamiltonians::two_particle_spring h{v.at("mass"), v.at("stiffness")};
             return model<4>(h, stacked(hamiltonians::two_particle_spring::initial_state()),
                          exact_flow(h, hamiltonians::two_particle_spring::initial_state()));
         }},
        {"morse", "Morse 1929: H = p^2/(2m) + D (1 - exp(-a (q - r0)))^2; q0 = 0.5, p0 = 0.4; exact while bound (E < D)",
         {positive("mass", 1, "m"), positive("depth", 1, "well depth D"), positive("width", 1, "a, inverse width"),
          any("position", 0, "r0, the minimum")},
         true,
         [](const parameter_values& v) {
             const hamiltonians::morse h{v.at("mass"), v.at("depth"), v.at("width"), v.at("position")};
             const S1 x0(V1(0.5), V1(0.4));
             const bool bound = energy(h, x0) < h.depth;
             return model<1>(h, stacked(x0), bound ? exact_flow(h, x0) : nullptr);
         }},
        {"double_well", "H = p^2/2 + barrier (q^2 - 1)^2; q0 = 0.5, p0 = 0.3",
         {nonnegative("barrier", 1, "barrier height at q = 0")}, false,
         [](const parameter_values& v) { return model<1>(hamiltonians::double_well{v.at("barrier")}, {0.5, 0.3}); }},
        {"toda", "periodic Toda lattice (Toda 1967); q = 0, p_k = cos(2 pi k / n)",
         {count("n", 8, 2, "number of masses")}, false,
         [](const parameter_values& v) {
             const auto n = std::size_t(v.at("n"));
             std::vector<double> x0(2 * n, 0.0);
             for (std::size_t k = 0; k < n; ++k) x0[n + k] = std::cos(2 * std::acos(-1.0) * double(k) / double(n));
             return model(hamiltonians::toda{}, x0);
         }},
        {"damped_oscillator",
         "m x'' = -k x - b v + F0 cos(Omega t): not Hamiltonian (classic methods and Odeint only); x0 = 1, v0 = 0; exact",
         {positive("mass", 1, "m"), positive("stiffness", 1, "k"), nonnegative("damping", 0.3, "b"),
          any("drive_amplitude", 0, "F0"), nonnegative("drive_frequency", 0, "Omega")},
         true,
         [](const parameter_values& v) {
             const hamiltonians::damped_driven_oscillator o{v.at("mass"), v.at("stiffness"), v.at("damping"),
                                                            v.at("drive_amplitude"), v.at("drive_frequency")};
             const S1 x0(V1(1.0), V1(0.0));
             return model<1>(o, stacked(x0), exact_flow(o, x0));
         }},
    };
    return entries;
}

}  // namespace

bool parameter::accepts(double v) const {
    if (!std::isfinite(v)) return false;
    if (v < low || (low_open && v == low) || v > high || (high_open && v == high)) return false;
    return !integer || v == std::floor(v);
}

std::string parameter::expected() const {
    const std::string what = integer ? "an integer" : "a finite number";
    const auto shortest = [this](double v) { return integer ? std::to_string(std::int64_t(v)) : app::shortest(v); };
    const bool bounded_below = std::isfinite(low), bounded_above = std::isfinite(high);
    if (bounded_below && bounded_above)
        return what + " in " + (low_open ? "(" : "[") + shortest(low) + ", " + shortest(high) +
               (high_open ? ")" : "]");
    if (bounded_below) return what + (low_open ? " > " : " >= ") + shortest(low);
    if (bounded_above) return what + (high_open ? " < " : " <= ") + shortest(high);
    return what;
}

const parameter* system_entry::find(const std::string& parameter_name) const {
    for (const auto& p : parameters)
        if (p.name == parameter_name) return &p;
    return nullptr;
}

const std::vector<system_entry>& systems() { return registry(); }

const system_entry* find_system(const std::string& name) {
    for (const auto& s : registry())
        if (s.name == name) return &s;
    return nullptr;
}

std::vector<std::string> system_names() {
    std::vector<std::string> names;
    for (const auto& s : registry()) names.push_back(s.name);
    return names;
}

parameter_values with_defaults(const system_entry& entry, const parameter_values& given, const std::string& where) {
    parameter_values v;
    for (const auto& p : entry.parameters) v[p.name] = p.value;
    for (const auto& [name, value] : given) {
        const parameter* p = entry.find(name);
        if (!p) throw invalid_argument(where + ": " + entry.name + " has no parameter '" + name + "'");
        if (!p->accepts(value))
            throw invalid_argument(where + ": " + entry.name + " " + name + " = " + shortest(value) +
                                   "; expected " + p->expected());
        v[name] = value;
    }
    return v;
}

problem make_problem(const std::string& system, const parameter_values& given, const std::vector<double>& q0,
                     const std::vector<double>& p0, const std::string& where) {
    const system_entry* entry = find_system(system);
    if (!entry) throw invalid_argument(where + ": unknown system '" + system + "'");
    problem p;
    try {
        p = entry->build(with_defaults(*entry, given, where));
    } catch (const invalid_argument& e) {
        const std::string what = e.what();
        throw invalid_argument(what.rfind(where, 0) == 0 ? what : where + ": " + what);
    }
    p.system = system;
    p.form.negative_potential = entry->negative_potential;
    if (!q0.empty()) {  // the scene's own initial state: the exact solution no longer applies
        if (q0.size() != p.degrees_of_freedom || p0.size() != q0.size())
            throw invalid_argument(where + ": initial q has " + std::to_string(q0.size()) + " and p " +
                                   std::to_string(p0.size()) + " values; " + system + " expects " +
                                   std::to_string(p.degrees_of_freedom) + " each");
        p.x0 = q0;
        p.x0.insert(p.x0.end(), p0.begin(), p0.end());
        p.exact = nullptr;
    }
    return p;
}

}  // namespace sympl::app
