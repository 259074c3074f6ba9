// Fill-reducing orderings of a scene's nodes for the sparse Cholesky of the
// Newton matrix: nested dissection (METIS_NodeND, through CHOLMOD) of the
// node graph, in which two free nodes are adjacent when a term couples them.
//
// Ordering nodes, not degrees of freedom, is the same elimination for the
// matrix (each node's dimension unknowns stay together; the supernodes
// follow) on a graph with dimension times fewer vertices and dimension^2
// fewer edges, so METIS runs several times faster. It also lets Ceres 2.1,
// which has no nested-dissection option, factorise in this order: its
// linear_solver_ordering with one elimination group per node, in this order,
// is honoured exactly by the constrained AMD it runs for SUITE_SPARSE
// (solver/trust_region_solver.h).
#pragma once

#include <vector>

#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

// The free nodes that some term touches, in nested-dissection order (first
// eliminated first). Empty if METIS fails (then callers fall back to AMD).
std::vector<int> NestedDissectionNodeOrder(const IncrementalPotential& potential,
                                           const State& state);

}  // namespace ipstep
