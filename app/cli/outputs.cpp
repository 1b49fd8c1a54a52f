#include "outputs.h"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/input_file.h"
#include "base/text.h"
#include "common.h"

namespace dp::cli {

namespace {

namespace fs = std::filesystem;


fs::path folder_of(const std::string& path) {
    const fs::path folder = fs::path(path).parent_path();
    return folder.empty() ? fs::path(".") : folder;
}

std::string quoted(const fs::path& p) { return "'" + shorten_path(p.string()) + "'"; }

fs::path absolute_path(const fs::path& p) {
    std::error_code ec;
    return fs::absolute(p, ec).lexically_normal();
}

/// A path as a message shows it: relative to the working folder when it lies inside it.
fs::path shown_path(const fs::path& p) {
    std::error_code ec;
    const fs::path relative = absolute_path(p).lexically_relative(fs::current_path(ec));
    return !relative.empty() && *relative.begin() != ".." ? relative : p;
}

/// Where an output may go at all: a path, not a folder, in a folder that exists, with a name
/// its file system takes.
void check_place(const Output& out) {
    if (out.path.empty()) throw InputError(out.path, out.option, "no output file given");
    std::error_code ec;
    if (fs::is_directory(out.path, ec)) throw InputError(out.path, out.option, "is a directory");
    const fs::path folder = folder_of(out.path);
    if (!fs::is_directory(folder, ec))
        throw InputError(out.path, out.option, "folder " + quoted(folder) + " does not exist");
    const size_t name = fs::path(out.path).filename().string().size(), limit = file_name_limit(folder.string());
    if (name > limit)
        throw InputError(out.path, out.option,
                         "its name is " + std::to_string(name) + " bytes long, more than the " +
                             std::to_string(limit) + " its file system takes");
}

/// Two outputs of one command are one file: the second would replace the first.
bool same_file(const std::string& a, const std::string& b) {
    const auto sa = file_status(a), sb = file_status(b);
    if (sa && sb) return sa->st_dev == sb->st_dev && sa->st_ino == sb->st_ino;
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(a, ec), ec) == fs::weakly_canonical(fs::absolute(b, ec), ec);
}

/// The replacement is a rename in the folder: the folder must take it, and a read-only file
/// (or folder) is taken to mean "keep this" unless --force says otherwise.
void check_replaceable(const Output& out, bool force) {
    const fs::path folder = folder_of(out.path);
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw InputError(out.path, out.option, "folder " + quoted(folder) + " is not writable");
    const auto dir = file_status(folder.string());
    // Checked on the mode too: access() lets root write anything.
    if (!force && dir && (dir->st_mode & 0222) == 0)
        throw InputError(out.path, out.option,
                         "folder " + quoted(folder) + " is read-only: pass --force to write there anyway");
    const auto file = file_status(out.path);
    if (!file) return;  // a new file
    const uid_t me = ::geteuid();
    if (dir && (dir->st_mode & S_ISVTX) && me != 0 && file->st_uid != me && dir->st_uid != me)
        throw InputError(out.path, out.option,
                         "belongs to another user, and folder " + quoted(folder) +
                             " lets only a file's owner replace it: write elsewhere");
    const bool read_only = ::access(out.path.c_str(), W_OK) != 0 || (file->st_mode & 0222) == 0;
    if (read_only && !force)
        throw InputError(out.path, out.option, "is read-only: pass --force to replace it");
}

/// Free inodes and space, the outputs on one file system counted together.
void check_room(const std::vector<Output>& outputs) {
    std::map<dev_t, double> needed;
    for (const Output& out : outputs) {
        const fs::path folder = folder_of(out.path);
        struct statvfs vfs {};
        const auto dir = file_status(folder.string());
        if (!dir || ::statvfs(folder.c_str(), &vfs) != 0) continue;  // the write will say what fails
        // f_files 0: a file system without a fixed table of files (btrfs), never short of one.
        if (vfs.f_files > 0 && vfs.f_favail == 0)
            throw InputError(out.path, out.option,
                             "its folder " + quoted(folder) +
                                 " is on a file system with no free inode (no new file can be made there): "
                                 "delete some files or write elsewhere");
        double& need = needed[dir->st_dev];
        need += out.bytes;
        const double available = double(vfs.f_bavail) * double(vfs.f_frsize);
        if (need <= available) continue;
        throw InputError(out.path, out.option,
                         std::string(outputs.size() > 1 ? "the outputs need" : "the output needs") + " up to " +
                             format_bytes(need) + " but its folder " + quoted(folder) + " has only " +
                             format_bytes(available) + " free: free some space or write elsewhere");
    }
}

}  // namespace

void check_outputs(const std::vector<Output>& outputs, const ReadSet& inputs, bool force) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        const Output& out = outputs[i];
        check_place(out);
        const bool in_place = !out.updates.empty() && same_file(out.updates, out.path);
        if (const ReadFile* in = in_place ? nullptr : inputs.find(out.path)) {
            std::string what = in->what;
            // Through a link or another spelling: which file it is.
            if (absolute_path(out.path) != absolute_path(in->path)) what = quoted(shown_path(in->path)) + ", " + what;
            throw InputError(out.path, out.option, "is " + what + ": an output never replaces an input; choose another name");
        }
        for (size_t k = 0; k < i; ++k)
            if (same_file(outputs[k].path, out.path))
                throw InputError(out.path, out.option, "is also the output of " + outputs[k].option);
        check_replaceable(out, force);
    }
    check_room(outputs);
}

void add_force_flag(CLI::App* sub, bool& force) {
    sub->add_flag("--force", force,
                  "Replace output files (or write in folders) that are read-only; an output that is one of "
                  "the command's inputs is refused all the same");
}

double image_output_bytes(const std::string& path, const OutputFormat& format, int width, int height,
                          int channels) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    double per_sample = 1;  // PNG and TIFF 8 bits
    if (ext == ".exr")
        per_sample = format.half ? 2 : 4;
    else if (ext == ".jpg" || ext == ".jpeg")
        per_sample = 2;  // at quality 100 a JPEG of noise takes more than its raw 8 bits
    else if (format.bits == 32)
        per_sample = 4;  // TIFF, linear float
    else if (format.bits == 16 || ((ext == ".tif" || ext == ".tiff") && format.bits == 0))
        per_sample = 2;  // a TIFF is 16 bits unless told otherwise
    const double samples = double(width) * double(height) * double(channels);
    // Deflate's worst case on incompressible data is a fraction of a percent; headers, the
    // photo's metadata and an ICC profile fit in the fixed part.
    return samples * per_sample * 1.01 + 256.0 * 1024;
}

}  // namespace dp::cli
