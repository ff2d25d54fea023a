#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/methods/extrapolation.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/extrapolation.hpp> is deprecated: include <sympl/methods/extrapolation.hpp>")
#endif
#include "methods/extrapolation.hpp"
