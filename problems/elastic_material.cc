#include "problems/elastic_material.h"

namespace ipstep {

const char* ElasticModelName(ElasticModel model) {
  switch (model) {
    case ElasticModel::kLinear:
      return "linear";
    case ElasticModel::kStvk:
      return "stvk";
    case ElasticModel::kFixedCorotated:
      return "fixed_corotated";
    case ElasticModel::kNeoHookean:
      return "neo_hookean";
  }
  return "?";
}

bool ParseElasticModel(const std::string& name, ElasticModel* model) {
  for (ElasticModel m : {ElasticModel::kLinear, ElasticModel::kStvk, ElasticModel::kFixedCorotated,
                         ElasticModel::kNeoHookean}) {
    if (name == ElasticModelName(m)) {
      *model = m;
      return true;
    }
  }
  return false;
}

const char* MassDistributionName(MassDistribution masses) {
  return masses == MassDistribution::kUniform ? "uniform" : "lumped";
}

bool ParseMassDistribution(const std::string& name, MassDistribution* masses) {
  for (MassDistribution m : {MassDistribution::kLumped, MassDistribution::kUniform}) {
    if (name == MassDistributionName(m)) {
      *masses = m;
      return true;
    }
  }
  return false;
}

}  // namespace ipstep
