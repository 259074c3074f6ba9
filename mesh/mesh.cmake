# Meshes (mesh/) and the elastic solid's scene data, compiled into the scene
# library (problems/CMakeLists.txt) because the scene loader builds solids.
# Gmsh (libgmsh-dev) is required; Debian ships no CMake config for it.
find_path(IPSTEP_GMSH_INCLUDE_DIR gmsh.h)
find_library(IPSTEP_GMSH_LIBRARY NAMES gmsh)
if(NOT IPSTEP_GMSH_INCLUDE_DIR OR NOT IPSTEP_GMSH_LIBRARY)
  message(FATAL_ERROR "Gmsh not found (gmsh.h, libgmsh): install libgmsh-dev "
                      "(tools/install_dependencies.sh)")
endif()
# mesh/gmsh_mesh.cc loads the library with dlopen on first use (not linked:
# loading it costs every program 0.28 s at start). Its real file, so that the
# runtime package's file is found without the -dev symlink, named by its
# soname (libgmsh.so.4.8, not the patch version's file name).
get_filename_component(IPSTEP_GMSH_LIBRARY_FILE "${IPSTEP_GMSH_LIBRARY}" REALPATH)
string(REGEX REPLACE "(\\.so\\.[0-9]+\\.[0-9]+)\\.[0-9]+$" "\\1" IPSTEP_GMSH_LIBRARY_FILE
       "${IPSTEP_GMSH_LIBRARY_FILE}")
message(STATUS "Gmsh: ${IPSTEP_GMSH_LIBRARY_FILE} (loaded on first use)")
set(ipstep_mesh_sources
  ${PROJECT_SOURCE_DIR}/mesh/gmsh_mesh.cc
  ${PROJECT_SOURCE_DIR}/mesh/mesh_boundary.cc
  ${PROJECT_SOURCE_DIR}/mesh/simplex_mesh.cc
  ${PROJECT_SOURCE_DIR}/mesh/structured_mesh.cc
  ${PROJECT_SOURCE_DIR}/energies/elasticity/elastic_material.cc
  ${PROJECT_SOURCE_DIR}/problems/solid_loader.cc
)
