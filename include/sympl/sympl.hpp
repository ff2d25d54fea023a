#pragma once
// sympl: symplectic splitting methods for separable Hamiltonians. Everything.
#include "catalog.hpp"
#include "convergence.hpp"
#include "dual.hpp"
#include "error.hpp"
#include "hamiltonian.hpp"
#include "integrate.hpp"
#include "phase_space.hpp"
#include "splitting_stepper.hpp"
#include "table.hpp"
