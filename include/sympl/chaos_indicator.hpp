#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/analysis/chaos_indicator.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/chaos_indicator.hpp> is deprecated: include <sympl/analysis/chaos_indicator.hpp>")
#endif
#include "analysis/chaos_indicator.hpp"
