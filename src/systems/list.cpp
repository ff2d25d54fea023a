// sympl's own systems, in the order `sympl systems` lists them: one line
// each (the entry itself is in systems/<name>.cpp). A program's registry is
// program_systems(), which sympl_add_program writes (systems.hpp).
#include <vector>

#include "running/systems.hpp"

namespace sympl::app {

system_entry harmonic_oscillator_entry();
system_entry pendulum_entry();
system_entry kepler_entry();
system_entry kepler_3d_entry();
system_entry relativistic_pendulum_entry();
system_entry henon_heiles_entry();
system_entry fpu_beta_entry();
system_entry stiff_fpu_entry();
system_entry outer_solar_system_entry();
system_entry two_particle_spring_entry();
system_entry morse_entry();
system_entry double_well_entry();
system_entry toda_entry();
system_entry damped_oscillator_entry();
system_entry charged_particle_entry();
system_entry charged_uniform_entry();
system_entry double_pendulum_entry();
system_entry product_hamiltonian_entry();

std::vector<system_entry> builtin_systems() {
    return {
        harmonic_oscillator_entry(),
        pendulum_entry(),
        kepler_entry(),
        kepler_3d_entry(),
        relativistic_pendulum_entry(),
        henon_heiles_entry(),
        fpu_beta_entry(),
        stiff_fpu_entry(),
        outer_solar_system_entry(),
        two_particle_spring_entry(),
        morse_entry(),
        double_well_entry(),
        toda_entry(),
        damped_oscillator_entry(),
        charged_particle_entry(),
        charged_uniform_entry(),
        double_pendulum_entry(),
        product_hamiltonian_entry(),
    };
}

}  // namespace sympl::app
