// The "elasticity" effect: one energy term per element of the scene's solid
// (problems/solid.h; energies/elasticity/element_energy.h) and the step
// filter that keeps every element positively oriented
// (energies/elasticity/inversion_filter.h).
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "core/term.h"
#include "energies/term_builder.h"
#include "problems/elastic_material.h"

namespace ipstep {

// The potential term of one element: `rest` holds its dimension + 1 rest
// positions (positively oriented), `nodes` its node indices.
Term MakeElasticElementTerm(const ElasticMaterial& material, int dimension,
                            const double* const* rest, const std::array<int, 4>& nodes);

// The effect's factory (EffectRegistry): needs a scene with a "solid".
std::string BuildElasticity(TermBuilder& builder, const nlohmann::json& parameters);

}  // namespace ipstep
