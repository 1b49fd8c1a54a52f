#pragma once
// Where the files scripts/install-deps.sh puts in the repository's .deps folder are looked for.
#include <filesystem>
#include <vector>

namespace dp {

/// `<dir>/.deps/<relative>` for every folder above the running executable (build/app/diffphoton
/// and build/tests/x reach the repository's .deps), then in the source tree, without repeats.
std::vector<std::filesystem::path> deps_candidates(const std::filesystem::path& relative);
/// `<dir>/<relative>` the same way: the repository's own files (farm/) beside a build.
std::vector<std::filesystem::path> tree_candidates(const std::filesystem::path& relative);

}  // namespace dp
