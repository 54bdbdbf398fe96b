// This build's identity: version, git commit (or tree hash), compiler, flags and build type,
// generated at build time (cmake/BuildInfo.cmake). Every output's provenance records it
// (io/provenance.hpp), and the grid runner stamps its tiles with it (run/grid.hpp).
#pragma once

#include <string>

namespace bouncer {

struct BuildInfo {
  std::string version, commit, compiler, flags, build_type;
};
const BuildInfo& build_info();

}  // namespace bouncer
