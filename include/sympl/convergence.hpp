#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/analysis/convergence.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/convergence.hpp> is deprecated: include <sympl/analysis/convergence.hpp>")
#endif
#include "analysis/convergence.hpp"
