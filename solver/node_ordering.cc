#include "solver/node_ordering.h"

#include <algorithm>

#include <cholmod.h>

#include "solver/serial_openmp.h"

namespace ipstep {

std::vector<int> NestedDissectionNodeOrder(const IncrementalPotential& potential,
                                           const State& state) {
  // Free nodes touched by a term, numbered 0..n-1 in node order.
  std::vector<int> index(state.num_nodes(), -1);
  std::vector<int> nodes;
  for (const Term& term : potential.terms()) {
    for (int node : term.nodes) {
      if (state.is_free(node) && index[node] < 0) index[node] = 1;
    }
  }
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (index[i] < 0) continue;
    index[i] = static_cast<int>(nodes.size());
    nodes.push_back(i);
  }
  const int n = static_cast<int>(nodes.size());
  if (n == 0) return nodes;
  // The upper triangle of the node graph (with the diagonal), column by column.
  std::vector<std::vector<int>> rows(n);
  for (int c = 0; c < n; ++c) rows[c].push_back(c);
  for (const Term& term : potential.terms()) {
    for (int a : term.nodes) {
      for (int b : term.nodes) {
        const int ia = index[a], ib = index[b];
        if (ia >= 0 && ib >= 0 && ia < ib) rows[ib].push_back(ia);
      }
    }
  }
  std::vector<int> column_start(n + 1, 0);
  std::vector<int> row_index;
  for (int c = 0; c < n; ++c) {
    std::sort(rows[c].begin(), rows[c].end());
    rows[c].erase(std::unique(rows[c].begin(), rows[c].end()), rows[c].end());
    row_index.insert(row_index.end(), rows[c].begin(), rows[c].end());
    column_start[c + 1] = static_cast<int>(row_index.size());
    std::vector<int>().swap(rows[c]);
  }
  cholmod_sparse graph{};
  graph.nrow = graph.ncol = static_cast<size_t>(n);
  graph.nzmax = row_index.size();
  graph.p = column_start.data();
  graph.i = row_index.data();
  graph.x = nullptr;
  graph.stype = 1;  // symmetric, upper triangle stored
  graph.itype = CHOLMOD_INT;
  graph.xtype = CHOLMOD_PATTERN;
  graph.dtype = CHOLMOD_DOUBLE;
  graph.sorted = 1;
  graph.packed = 1;

  const SerialOpenMp serial;
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  std::vector<int> permutation(n);
  const bool ok = cholmod_metis(&graph, nullptr, 0, /*postorder=*/1, permutation.data(), &common);
  cholmod_finish(&common);
  if (!ok) return {};
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = nodes[permutation[k]];
  return order;
}

}  // namespace ipstep
