// An obstacle from its scene entry (an element of "contact.obstacles",
// docs/contact.md "Scene keys"): "type" picks the shape, which reads its keys;
// every shape takes an optional "velocity", "until" (its stop time) and "mu"
// (its friction coefficient). Problems are InputErrors naming
// the key (core/json_node.h). The obstacle's name is the entry's path.
#pragma once

#include "contact/obstacle.h"
#include "core/json_node.h"

namespace ipstep {

ObstaclePtr ReadObstacle(const JsonNode& entry, int dimension);

}  // namespace ipstep
