// Reading a scene's "solid" object: the mesh of an elastic solid and its
// material. Every problem is one InputError naming the file and the key
// (e.g. "scene.json: solid.poisson_ratio: must be in (-1, 0.5), got 0.5").
//
//   "solid": {
//     "mesh": {"shape": "rectangle", "size": [w, h], "cells": [nx, ny], "origin": [x, y]}
//           | {"shape": "box", "size": [w, h, d], "cells": [nx, ny, nz], "origin": [...]}
//           | {"gmsh": "rectangle" | "box", "size": [...], "origin": [...], "element_size": s}
//           | {"gmsh": "disk" | "ball", "center": [...], "radius": r, "element_size": s}
//           | {"file": "mesh.msh"}   (Gmsh 2.2 or 4.x, relative to the scene file)
//           | {"nodes": [[x, y], ...], "elements": [[i, j, k], ...]}
//     "model": "neo_hookean" | "stvk" | "fixed_corotated" | "linear"   (default neo_hookean)
//     "youngs_modulus": E > 0 [Pa], "poisson_ratio": nu in (-1, 0.5),
//     "density": rho > 0 [kg/m^2 in 2D, kg/m^3 in 3D],
//     "plane": "strain" | "stress"   (2D only; default strain)
//     "masses": "lumped" | "uniform"   (default lumped: each element gives
//               density * measure / (d + 1) to each of its nodes; uniform:
//               every node density * total measure / node count)
//   }
//
// Rejected as well: repeated elements (the same nodes in any order), a mesh
// file of another dimension, not a regular file or with a NUL in its path,
// more than limits::kMaxNodes nodes, node masses outside [kMinMass, kMaxMass],
// Gmsh shapes smaller than limits::kMinGmshLength.
//
// Node sets, usable by name in "pinned" and "moving": structured meshes
// "x_min", "x_max", "y_min", "y_max" ("z_min", "z_max"); Gmsh meshes their
// physical groups' names; every mesh "boundary" and "all".
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "problems/solid.h"

namespace ipstep {

// `path` is the key path of `value` ("solid"), `source` the scene file.
Solid ReadSolid(const nlohmann::json& value, int dimension, const std::string& source,
                const std::string& path = "solid");

}  // namespace ipstep
