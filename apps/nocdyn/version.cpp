// `nocdyn --version`: the version and the commit, from the header CMake generates at configure
// time (the only file that includes it, so that a new commit recompiles only this one).
#include "version.hpp"

#include <string>

#include "app.hpp"

namespace nocdyn::cli {

std::string versionText() { return std::string("nocdyn ") + NOCDYN_VERSION + " (commit " + NOCDYN_GIT_COMMIT + ")"; }

}  // namespace nocdyn::cli
