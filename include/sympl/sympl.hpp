#pragma once
// sympl: symplectic splitting methods for separable Hamiltonians. Everything
// but the Boost.Odeint interop (odeint.hpp), which pulls in all of Odeint, and
// the 113-bit order measurement (table_order.hpp), which pulls in Boost.Multiprecision,
// and ensembles over MPI ranks (ensemble_mpi.hpp), which need Boost.MPI.
#include "adaptive.hpp"
#include "batch.hpp"
#include "catalog.hpp"
#include "chaos_indicator.hpp"
#include "classic_steppers.hpp"
#include "convergence.hpp"
#include "dual.hpp"
#include "ensemble.hpp"
#include "equations_of_motion.hpp"
#include "extrapolation.hpp"
#include "error.hpp"
#include "hamiltonian.hpp"
#include "integrate.hpp"
#include "phase_space.hpp"
#include "phase_space_measures.hpp"
#include "poincare_section.hpp"
#include "order_conditions.hpp"
#include "processing.hpp"
#include "richardson.hpp"
#include "splitting_stepper.hpp"
#include "table.hpp"
#include "time_transformation.hpp"
