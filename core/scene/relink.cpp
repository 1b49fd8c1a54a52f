#include "scene/relink.h"

#include <deque>
#include <map>
#include <system_error>
#include <utility>

namespace dp {

namespace fs = std::filesystem;

std::vector<InputFile> input_files(const Project& project) {
    std::vector<InputFile> files;
    for_each_input(project, [&](const InputRef& ref, const std::string& path) {
        InputFile f;
        f.ref = ref;
        f.stored = path;
        f.resolved = project.resolve(path);
        std::error_code ec;
        f.missing = !fs::is_regular_file(f.resolved, ec);
        files.push_back(std::move(f));
    });
    return files;
}

std::vector<InputFile> missing_inputs(const Project& project) {
    std::vector<InputFile> missing;
    for (InputFile& f : input_files(project))
        if (f.missing) missing.push_back(std::move(f));
    return missing;
}

std::string path_for_project(const fs::path& base_dir, const fs::path& file) {
    std::error_code ec;
    const fs::path abs = fs::absolute(file, ec).lexically_normal();
    if (base_dir.empty()) return abs.string();
    const fs::path rel = abs.lexically_relative(fs::absolute(base_dir, ec).lexically_normal());
    // The rule calibrate's new projects follow: inside the folder relative, elsewhere absolute.
    if (!rel.empty() && *rel.begin() != ".." && rel != ".") return rel.string();
    return abs.string();
}

bool set_input_path(Project& project, const std::string& field, const std::string& path) {
    bool found = false;
    for_each_input(project, [&](const InputRef& ref, std::string& stored) {
        if (ref.field != field) return;
        stored = path;
        found = true;
    });
    return found;
}

std::optional<fs::path> find_file_named(const std::string& name,
                                        const std::vector<fs::path>& folders, int depth,
                                        size_t max_entries) {
    if (name.empty()) return std::nullopt;
    size_t seen = 0;
    std::map<fs::path, int> searched;  ///< folder -> levels below it searched already
    for (const fs::path& folder : folders) {
        if (folder.empty()) continue;
        std::deque<std::pair<fs::path, int>> queue{{folder.lexically_normal(), 0}};
        while (!queue.empty()) {
            auto [dir, level] = queue.front();
            queue.pop_front();
            // A folder reached again (a subfolder of an earlier one) has nothing new, unless this
            // search goes deeper below it.
            auto [at, added] = searched.emplace(dir, depth - level);
            if (!added) {
                if (at->second >= depth - level) continue;
                at->second = depth - level;
            }
            std::error_code ec;
            fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
            for (; !ec && it != fs::directory_iterator(); it.increment(ec)) {
                if (++seen > max_entries) return std::nullopt;
                std::error_code e;
                const fs::file_status status = it->symlink_status(e);
                if (fs::is_directory(status)) {
                    if (level < depth) queue.emplace_back(it->path(), level + 1);
                } else if (it->path().filename() == name && fs::is_regular_file(it->path(), e)) {
                    return it->path();
                }
            }
        }
    }
    return std::nullopt;
}

}  // namespace dp
