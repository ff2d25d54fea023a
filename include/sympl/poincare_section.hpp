#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/analysis/poincare_section.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/poincare_section.hpp> is deprecated: include <sympl/analysis/poincare_section.hpp>")
#endif
#include "analysis/poincare_section.hpp"
