#pragma once
// Paths given to the tests by CMake.
#ifndef CARBONMESH_CLI
#error "CARBONMESH_CLI must be defined by the build"
#endif
#ifndef CARBONMESH_SHARED_DIR
#error "CARBONMESH_SHARED_DIR must be defined by the build"
#endif
