#pragma once
// The kernels of the drift-kick-drift Wisdom-Holman leapfrog (Wisdom, Holman
// & Touma 1996, Fields Inst. Commun. 10, 217, sec. on kernels; Rein, Tamayo &
// Brown 2019, MNRAS 489, 4632, their WHCKC): what stands in place of the
// middle kick(h). The composition kernel is built of the splitting's own
// flows; the lazy implementer's kernel (WHT96 eq. 10.6) is the kick at
// positions displaced along the accelerations, for Jacobi coordinates only.
// Why they cancel the corrected leapfrog's -h^2/24 [B,[A,B]], and the
// measurements that settle their signs, are in docs/planetary.md ("Kernels").
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../core/table.hpp"

namespace sympl {

// What stands between the drift-kick-drift leapfrog's two half drifts: the leapfrog's own kick, or Wisdom,
// Holman & Touma 1996's composition kernel, or their "lazy implementer's"
// kernel (Jacobi coordinates only).
enum class wh_kernel { kick, composition, lazy };

inline std::string kernel_name(wh_kernel k) {
    switch (k) {
        case wh_kernel::kick: return "kick";
        case wh_kernel::composition: return "composition";
        case wh_kernel::lazy: return "lazy";
    }
    return "unknown (" + std::to_string(int(k)) + ")";
}

// The composition kernel's two weights, a of the Kepler drifts and b of the
// side kicks, in units of the step: the kernel of Wisdom, Holman & Touma 1996
// (Fields Inst. Commun. 10, 217) with the sub-steps and weights of Rein,
// Tamayo & Brown 2019's WHCKC (MNRAS 489, 4632) as REBOUND's WHFast runs it
// (kernel "composition"). Only 2ab = 1/24 is forced by the theory.
inline constexpr coefficient composition_kernel_drift = 1.0L / 8;  // a (Kepler drifts), WHT96 / RTB2019
inline constexpr coefficient composition_kernel_kick = 1.0L / 6;   // b (kicks), WHT96 / RTB2019

// The lazy implementer's kernel: the kick(h) by the interaction at the
// positions displaced by this times h^2 times the interaction's acceleration
// (Wisdom, Holman & Touma 1996, eq. 10.6 as Rein, Tamayo & Brown 2019 cite
// it): to first order in the displacement the kick by the gradient of
// B + h^2/24 {B,{A,B}} (docs/planetary.md, "Kernels"; the sign by measurement).
inline constexpr coefficient lazy_kernel_displacement = 1.0L / 12;

// The kernel's sub-steps in place of kick(h), in time order, weights in units
// of h: Z(a, -b) kick(1) Z(-a, -b), Z(a, b) = drift(a) kick(b) drift(-2a) kick(-b) drift(a).
// The lazy kernel is one kick(1), which the stepper takes at displaced positions.
inline std::vector<substep> kernel_substeps(wh_kernel k) {
    if (k == wh_kernel::kick || k == wh_kernel::lazy) return {{substep::kick, 1}};
    if (k != wh_kernel::composition)
        throw invalid_argument("Wisdom-Holman kernel " + kernel_name(k) + "; expected kick, composition or lazy");
    const coefficient a = composition_kernel_drift, b = composition_kernel_kick;
    const auto Z = [](coefficient x, coefficient y) {
        return std::vector<substep>{{substep::drift, x}, {substep::kick, y}, {substep::drift, -2 * x},
                                    {substep::kick, -y}, {substep::drift, x}};
    };
    std::vector<substep> ops = Z(a, -b);
    ops.push_back({substep::kick, 1});
    for (const substep& o : Z(-a, -b)) ops.push_back(o);
    return ops;
}

}  // namespace sympl
