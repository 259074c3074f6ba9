#include "energies/term_builder.h"

namespace ipstep {

void TermBuilder::Add(TermKind kind, std::vector<int> nodes,
                      std::unique_ptr<ceres::CostFunction> cost,
                      std::unique_ptr<ceres::LossFunction> loss) {
  Term term;
  term.kind = kind;
  term.nodes = std::move(nodes);
  term.cost = std::move(cost);
  term.loss = std::move(loss);
  Add(std::move(term));
}

void TermBuilder::Add(Term term) {
  term.family = family_;
  potential_->AddTerm(std::move(term));
}

}  // namespace ipstep
