// An elastic solid of a scene: its mesh (the rest configuration; the scene's
// nodes are the mesh's nodes, in order) and its material. Read from the
// scene's "solid" object (problems/solid_loader.h); its energy is built by the
// "elasticity" effect (energies/elasticity/elasticity_effect.h).
#pragma once

#include <string>
#include <vector>

#include "mesh/simplex_mesh.h"
#include "problems/elastic_material.h"

namespace ipstep {

struct Solid {
  SimplexMesh mesh;
  ElasticMaterial material;
  std::string description;     // where the mesh came from, for reports
  std::vector<double> masses;  // per node [kg]: lumped or uniform (material.masses)
};

}  // namespace ipstep
