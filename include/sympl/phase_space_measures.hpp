#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/analysis/phase_space_measures.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/phase_space_measures.hpp> is deprecated: include <sympl/analysis/phase_space_measures.hpp>")
#endif
#include "analysis/phase_space_measures.hpp"
