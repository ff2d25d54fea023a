#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/parallel/ensemble_mpi.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/ensemble_mpi.hpp> is deprecated: include <sympl/parallel/ensemble_mpi.hpp>")
#endif
#include "parallel/ensemble_mpi.hpp"
