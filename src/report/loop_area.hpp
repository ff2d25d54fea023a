#pragma once
// The loop-area measure of a scene (output.loop_area): how well a method
// keeps the area of a small loop of initial conditions.
#include "running/runnable_system.hpp"

namespace sympl::app {

// Relative change of the area of a small loop of initial conditions around
// x0 in the (q_0, p_0) plane, carried by the method from t0 to t_end (-1 when
// the run is unstable).
double loop_area_error(const runnable_system& p, const method_spec& m, run_request rq, double t0, double t_end);

}  // namespace sympl::app
