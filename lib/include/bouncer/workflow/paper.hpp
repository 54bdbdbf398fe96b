// The paper's manifest (data/paper/manifest.toml) and the scenes of data/scenes/, compiled into
// the library (lib/CMakeLists.txt generates their source at configure time): reproduce runs
// from any directory, its manifest checks know which scenes exist, and a host that calls the
// library (not the bouncer binary) has them too. Editing a file re-runs the configure step.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "bouncer/io/scene.hpp"

namespace bouncer {

// The text of data/paper/manifest.toml as it was when the library was built.
std::string_view paper_manifest_text();

// How reports and messages name that manifest.
inline constexpr const char* kPaperManifestSource = "data/paper/manifest.toml (built in)";

// The scenes of data/scenes/: built_in_scenes() of io/scene.hpp (declared there, as `--scene`
// of every command reads them too). A manifest's `--scene PATH` must be one of its keys.

}  // namespace bouncer
