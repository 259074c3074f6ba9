#include "contact/collision_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace ipstep {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Graph {
  std::vector<std::vector<int>> neighbours;
};

Graph BuildGraph(const Scene& scene) {
  Graph g;
  g.neighbours.resize(scene.num_nodes());
  for (const Spring& s : scene.springs) {
    g.neighbours[s.i].push_back(s.j);
    g.neighbours[s.j].push_back(s.i);
  }
  for (auto& list : g.neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return g;
}

double Length(const Scene& scene, int i, int j) {
  const int dim = scene.dimension;
  double sum = 0.0;
  for (int k = 0; k < dim; ++k) {
    const double d = scene.positions[dim * j + k] - scene.positions[dim * i + k];
    sum += d * d;
  }
  return std::sqrt(sum);
}

// Counterclockwise angle in [0, 2 pi) from direction `from` to direction `to`.
double CcwAngle(double from_x, double from_y, double to_x, double to_y) {
  double angle = std::atan2(to_y, to_x) - std::atan2(from_y, from_x);
  while (angle < 0.0) angle += 2.0 * kPi;
  while (angle >= 2.0 * kPi) angle -= 2.0 * kPi;
  return angle;
}

// Outer boundary walk of the component containing `component` nodes (2D).
std::vector<int> OuterBoundary(const Scene& scene, const Graph& g, const std::vector<int>& nodes) {
  auto x = [&](int i) { return scene.positions[2 * i]; };
  auto y = [&](int i) { return scene.positions[2 * i + 1]; };
  int start = nodes.front();
  for (int i : nodes) {
    if (y(i) < y(start) || (y(i) == y(start) && x(i) < x(start))) start = i;
  }
  std::vector<int> walk = {start};
  int previous = -1, current = start;
  double back_x = 0.0, back_y = -1.0;  // pretend we arrived from below
  const size_t limit = 4 * scene.springs.size() + 4;
  int first_next = -1;
  while (walk.size() <= limit) {
    int best = -1;
    double best_angle = 10.0;
    for (int n : g.neighbours[current]) {
      const double dx = x(n) - x(current), dy = y(n) - y(current);
      if (dx == 0.0 && dy == 0.0) continue;
      double angle = CcwAngle(back_x, back_y, dx, dy);
      if (n == previous || angle == 0.0) angle = 2.0 * kPi;  // go back only at a dead end
      if (angle < best_angle) {
        best_angle = angle;
        best = n;
      }
    }
    if (best < 0) break;
    if (current == start) {
      if (first_next < 0) {
        first_next = best;
      } else if (best == first_next) {
        break;  // closed the loop
      }
    }
    walk.push_back(best);
    back_x = x(current) - x(best);
    back_y = y(current) - y(best);
    previous = current;
    current = best;
  }
  if (walk.size() > 1 && walk.back() == start) walk.pop_back();
  return walk;
}

}  // namespace

CollisionMesh BuildCollisionMesh(const Scene& scene) {
  CollisionMesh surface;
  const int n = scene.num_nodes();
  const Graph g = BuildGraph(scene);
  std::map<int, double> weight;
  if (scene.dimension == 3) {
    for (int i = 0; i < n; ++i) {
      double shortest = -1.0;
      for (int j : g.neighbours[i]) {
        const double l = Length(scene, i, j);
        if (l > 0.0 && (shortest < 0.0 || l < shortest)) shortest = l;
      }
      weight[i] = shortest > 0.0 ? shortest * shortest : 1.0;
    }
    for (int i = 0; i < n; ++i) {
      for (int j : g.neighbours[i]) {
        if (j <= i) continue;
        // Skip a spring that spans another node k (|ik| + |kj| = |ij| at rest).
        const double l = Length(scene, i, j);
        bool spans = false;
        for (int k : g.neighbours[i]) {
          if (k == j) continue;
          const double via = Length(scene, i, k) + Length(scene, k, j);
          spans |= std::binary_search(g.neighbours[j].begin(), g.neighbours[j].end(), k) &&
                   via <= l * (1.0 + 1e-9);
        }
        if (!spans && l > 0.0) surface.edges.push_back({i, j});
      }
    }
  } else {
    std::vector<int> component(n, -1);
    std::set<std::pair<int, int>> edges;
    for (int seed = 0; seed < n; ++seed) {
      if (component[seed] >= 0) continue;
      std::vector<int> nodes = {seed}, stack = {seed};
      component[seed] = seed;
      while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        for (int j : g.neighbours[i]) {
          if (component[j] < 0) {
            component[j] = seed;
            nodes.push_back(j);
            stack.push_back(j);
          }
        }
      }
      if (nodes.size() == 1) {
        weight[seed] = 1.0;
        continue;
      }
      const std::vector<int> walk = OuterBoundary(scene, g, nodes);
      for (size_t k = 0; k < walk.size(); ++k) {
        const int a = walk[k], b = walk[(k + 1) % walk.size()];
        if (a == b) continue;
        if (!edges.insert({std::min(a, b), std::max(a, b)}).second) continue;
        const double l = Length(scene, a, b);
        weight[a] += 0.5 * l;
        weight[b] += 0.5 * l;
      }
    }
    for (const auto& [a, b] : edges) surface.edges.push_back({a, b});
  }
  for (const auto& [node, w] : weight) {
    surface.nodes.push_back(node);
    surface.weights.push_back(w);
  }
  for (const auto& e : surface.edges) {
    surface.edge_weights.push_back(0.25 * (weight[e[0]] + weight[e[1]]));
  }
  if (scene.dimension == 3) {
    // Faces: 3-cliques i < j < k of the edge graph.
    std::vector<std::vector<int>> adjacent(n);
    for (const auto& e : surface.edges) {
      adjacent[e[0]].push_back(e[1]);
      adjacent[e[1]].push_back(e[0]);
    }
    for (auto& list : adjacent) std::sort(list.begin(), list.end());
    for (const auto& e : surface.edges) {
      const int i = std::min(e[0], e[1]), j = std::max(e[0], e[1]);
      for (int k : adjacent[i]) {
        if (k <= j || !std::binary_search(adjacent[j].begin(), adjacent[j].end(), k)) continue;
        // Collinear at rest (a spring along two others): no triangle.
        const double lij = Length(scene, i, j), ljk = Length(scene, j, k),
                     lik = Length(scene, i, k);
        const double longest = std::max({lij, ljk, lik});
        if (lij + ljk + lik - 2.0 * longest <= 1e-9 * longest) continue;
        surface.faces.push_back({i, j, k});
        surface.face_weights.push_back((weight[i] + weight[j] + weight[k]) / 12.0);
      }
    }
  }
  return surface;
}

}  // namespace ipstep
