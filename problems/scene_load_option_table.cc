#include "problems/scene_load_option_table.h"

#include "core/input_limits.h"

namespace ipstep {

const OptionTable<SceneLoadOptions>& SceneLoadOptionTable() {
  static const OptionTable<SceneLoadOptions> table = [] {
    OptionRow<SceneLoadOptions> grid =
        WithRange(MakeOptionRow<SceneLoadOptions>(
                      "grid_size", "SceneLoadOptions.grid_size", "grid_size", OptionType::kInt, 0LL,
                      "Override the node count per side of a scene's grid"),
                  2, limits::kMaxGridSize, "", "the scene's size");
    BindField(&SceneLoadOptions::grid_size, &grid);
    return OptionTable<SceneLoadOptions>{grid};
  }();
  return table;
}

}  // namespace ipstep
