#pragma once
// sympl: symplectic splitting methods for separable Hamiltonians, and the
// exactly solvable flows beyond them (damping, driving, non-separable H, the
// Kepler drift). Everything
// but the Boost.Odeint interop (interop/odeint.hpp), which pulls in all of
// Odeint, the 113-bit order measurement (analysis/table_order.hpp), which pulls
// in Boost.Multiprecision, and ensembles over MPI ranks
// (parallel/ensemble_mpi.hpp), which need Boost.MPI. docs/layout.md: the folders.
#include "core/dual.hpp"
#include "core/equations_of_motion.hpp"
#include "core/general_hamiltonian.hpp"
#include "core/error.hpp"
#include "core/hamiltonian.hpp"
#include "core/integrate.hpp"
#include "core/phase_space.hpp"
#include "core/splitting_loop.hpp"
#include "core/splitting_stepper.hpp"
#include "core/table.hpp"
#include "methods/adaptive.hpp"
#include "methods/catalog.hpp"
#include "methods/classic_steppers.hpp"
#include "methods/conformal_splitting.hpp"
#include "methods/dense_output.hpp"
#include "methods/extended_phase_space.hpp"
#include "methods/extrapolation.hpp"
#include "methods/gauss_collocation.hpp"
#include "methods/kepler_drift.hpp"
#include "methods/kepler_tangent.hpp"
#include "methods/planetary_coordinates.hpp"
#include "methods/processing.hpp"
#include "methods/richardson.hpp"
#include "methods/rkn_pairs.hpp"
#include "methods/time_transformation.hpp"
#include "methods/wisdom_holman.hpp"
#include "analysis/chaos_indicator.hpp"
#include "analysis/convergence.hpp"
#include "analysis/events.hpp"
#include "analysis/order_conditions.hpp"
#include "analysis/phase_space_measures.hpp"
#include "analysis/poincare_section.hpp"
#include "parallel/batch.hpp"
#include "parallel/ensemble.hpp"
