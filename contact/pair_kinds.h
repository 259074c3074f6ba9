// The registry of pair kinds the contact state is made of
// (contact/pair_set.h), in the order their terms are built.
#pragma once

#include <memory>
#include <vector>

#include "contact/pair_set.h"

namespace ipstep {

// The pair sets for `context`: one per kind that applies (obstacle kinds
// always; self-contact kinds when `self_contact`, reading their stiffness
// through `self_kappa`, or context.kappa when it is null). `initial`: the
// initial positions (broad-phase cell sizes).
std::vector<std::unique_ptr<PairSet>> MakePairSets(const PairSetContext& context, bool self_contact,
                                                   const double* initial,
                                                   const double* self_kappa = nullptr);

}  // namespace ipstep
