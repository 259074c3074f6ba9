// The triangles that fill a spring network, for pictures (io/frame_writer.h,
// tools/animate.py): a 2D body's cells, a 3D cloth's surface. Scenes carry
// springs, not faces, so the faces are derived: triangles of springs (three
// nodes joined pairwise) that are not degenerate at the initial positions and
// have no edge passing through a node (bending springs spanning two cells),
// smallest perimeter first, each kept only if it does not overlap a kept
// triangle across a shared edge (its third node on the same side of the edge).
// A square cell with both shear diagonals gives two triangles.
#pragma once

#include <array>
#include <vector>

#include "problems/scene.h"

namespace ipstep {

std::vector<std::array<int, 3>> SurfaceTriangles(const Scene& scene);

}  // namespace ipstep
