// The triangles drawn for a body of springs, for pictures (io/frame_writer.h,
// tools/animate.py): a 2D body's cells, a 3D cloth's surface.
#pragma once

#include <array>
#include <vector>

#include "problems/scene.h"

namespace ipstep {

// The surface triangles the scene declares (Scene::surface: a 3D grid's two
// per cell, a "surface" key's "triangles", a 3D solid's boundary) or, when it
// declares none (2D scenes, whose surface is edges), SpringTriangles(scene).
std::vector<std::array<int, 3>> SurfaceTriangles(const Scene& scene);

// The triangles guessed from the springs: triangles of springs (three nodes
// joined pairwise) that are not degenerate at the initial positions and have
// no edge passing through a node (bending springs spanning two cells),
// smallest perimeter first, each kept only if it does not overlap a kept
// triangle across a shared edge (its third node on the same side of the edge).
// A square cell with both shear diagonals gives two triangles.
std::vector<std::array<int, 3>> SpringTriangles(const Scene& scene);

}  // namespace ipstep
