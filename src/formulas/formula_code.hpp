#pragma once
// A scene's formulas (formula.hpp) written out as C functions, with their
// gradients by reverse mode, for machine_code.hpp to compile once per run.
// Only the parsed tree is written: every name becomes q[k], p[k], k[j] or a
// loop index, every number is printed back from its double, so nothing of
// the scene's text reaches the compiler (docs/formulas.md).
//
// The functions, for R = double (suffix _d) and R = long double (suffix _l);
// k holds the parameters' values as doubles, n the degrees of freedom:
//   R   sympl_T_R(const R* p, const double* k)
//   R   sympl_V_R(const R* q, const double* k)
//   void sympl_velocity_R(const R* p, R* v, const double* k, long n)  v = dT/dp
//   void sympl_force_R(const R* q, R* f, const double* k, long n)     f = -dV/dq
// or, for a general H(q, p):
//   R   sympl_H_R(const R* q, const R* p, const double* k)
//   void sympl_dH_dq_R(const R* q, const R* p, R* out, const double* k, long n)
//   void sympl_dH_dp_R(const R* q, const R* p, R* out, const double* k, long n)
//
// The values are computed in the interpreter's order (formula_eval.hpp),
// operation for operation, so both give the same bits for T, V and H.
// Gradients: a forward pass stores each node's value, a backward pass adds
// each node's adjoint into its operands (Griewank & Walther, Evaluating
// Derivatives, 2nd ed., ch. 3); a sum's terms are computed again inside its
// backward loop rather than stored, so memory stays that of one term.
#include <string>

#include "formulas/formula.hpp"

namespace sympl::app::formulas {

// The C source of a separable system's four functions (both precisions).
std::string separable_source(const formula& T, const formula& V);

// The C source of a general H's three functions (both precisions).
std::string general_source(const formula& H);

}  // namespace sympl::app::formulas
