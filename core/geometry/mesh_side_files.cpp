#include "geometry/mesh_side_files.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string_view>

#include "base/text.h"
#include "geometry/gltf_json.h"
#include "base/byte_order.h"

namespace dp {

namespace {

namespace fs = std::filesystem;


std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

std::vector<std::string> words(const std::string& s) {
    std::istringstream in(s);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

/// A path as a mesh file writes it: Windows separators read as '/' (files written on Windows),
/// "file://" dropped, as the mesh loader resolves textures.
fs::path written_path(std::string text) {
    std::replace(text.begin(), text.end(), '\\', '/');
    if (text.rfind("file://", 0) == 0) text = text.substr(7);
    return fs::path(text);
}

fs::path resolved(const fs::path& folder, const std::string& text) {
    const fs::path p = written_path(text);
    return p.is_absolute() ? p : folder / p;
}

/// The files collected, each existing path once.
class SideFiles {
public:
    /// `text` as a file written relative to `folder`, if it exists.
    void add(const fs::path& folder, const std::string& text, MeshSideFile::Kind kind, const fs::path& via = {}) {
        if (!text.empty()) add(resolved(folder, text), kind, via);
    }
    void add(const fs::path& full, MeshSideFile::Kind kind, const fs::path& via = {}) {
        std::error_code ec;
        if (!fs::is_regular_file(full, ec)) return;
        if (seen_.insert(full.lexically_normal().string()).second) files_.push_back({full, kind, via});
    }
    std::vector<MeshSideFile> take() { return std::move(files_); }

private:
    std::set<std::string> seen_;
    std::vector<MeshSideFile> files_;
};

/// How many values an MTL texture option takes ("-o u [v [w]]" takes one to three numbers).
int option_values(const std::string& option, bool& up_to_three) {
    up_to_three = option == "-o" || option == "-s" || option == "-t";
    if (up_to_three) return 3;
    if (option == "-mm") return 2;
    return 1;  // -blendu, -blendv, -boost, -texres, -clamp, -bm, -imfchan, -type
}

bool is_number(const std::string& s) {
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return !s.empty() && end && *end == '\0';
}

/// The texture named by an MTL map statement's arguments: what follows the options, taken
/// whole (Assimp reads the rest of the line) and as its last word.
std::vector<std::string> map_names(const std::vector<std::string>& args) {
    size_t i = 0;
    while (i < args.size() && args[i].size() > 1 && args[i][0] == '-' && !is_number(args[i])) {
        bool up_to_three = false;
        const int n = option_values(args[i++], up_to_three);
        for (int k = 0; k < n && i < args.size(); ++k) {
            if (up_to_three && k > 0 && !is_number(args[i])) break;
            ++i;
        }
    }
    if (i >= args.size()) return {};
    std::string whole = args[i];
    for (size_t k = i + 1; k < args.size(); ++k) whole += " " + args[k];
    return {whole, args.back()};
}

bool is_map_keyword(const std::string& key) {
    static const std::set<std::string> kOthers = {"bump", "disp", "decal", "refl", "norm"};
    return key.rfind("map_", 0) == 0 || kOthers.count(key) > 0;
}

/// The textures of material library `mtl`, relative to its own folder or to the OBJ's (the
/// mesh loader resolves them from the OBJ's).
void add_mtl_textures(const fs::path& mtl, const fs::path& obj_folder, SideFiles& out) {
    std::ifstream in(mtl, std::ios::binary);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> w = words(line);
        if (w.size() < 2 || !is_map_keyword(ascii_lower(w[0]))) continue;
        w.erase(w.begin());
        for (const std::string& name : map_names(w)) {
            out.add(mtl.parent_path(), name, MeshSideFile::Kind::Texture, mtl);
            out.add(obj_folder, name, MeshSideFile::Kind::Texture, mtl);
        }
    }
}

void add_obj_files(const fs::path& obj, SideFiles& out) {
    std::ifstream in(obj, std::ios::binary);
    const fs::path folder = obj.parent_path();
    std::vector<fs::path> libraries;
    bool named_missing = false;
    for (std::string line; std::getline(in, line);) {
        const size_t start = line.find_first_not_of(" \t");
        if (start == std::string::npos || line.compare(start, 6, "mtllib") != 0) continue;
        const std::string rest = trim(line.substr(start + 6));
        std::vector<std::string> names = words(rest);
        if (names.size() > 1) names.push_back(rest);  // Assimp reads the rest of the line as one name
        for (const std::string& name : names) {
            const fs::path full = resolved(folder, name);
            std::error_code ec;
            if (fs::is_regular_file(full, ec))
                libraries.push_back(full);
            else
                named_missing = true;
        }
    }
    // Assimp reads "<mesh>.mtl" when a library it is told of cannot be opened.
    if (named_missing) {
        fs::path fallback = obj;
        fallback.replace_extension(".mtl");
        std::error_code ec;
        if (fs::is_regular_file(fallback, ec)) libraries.push_back(fallback);
    }
    for (const fs::path& mtl : libraries) {
        out.add(mtl, MeshSideFile::Kind::MaterialFile);
        add_mtl_textures(mtl, folder, out);
    }
}

/// "%20" and the like decoded, as URIs in glTF files are.
std::string uri_decoded(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
            std::isxdigit((unsigned char)uri[i + 2])) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

void add_gltf_files(const fs::path& path, SideFiles& out) {
    const GltfJson gltf = parse_gltf_json(gltf_json_text(path.string()));
    const nlohmann::json& doc = gltf.doc;
    if (doc.is_discarded() || !doc.is_object()) return;
    using Kind = MeshSideFile::Kind;
    const std::pair<const char*, Kind> kLists[] = {{"buffers", Kind::Buffer}, {"images", Kind::Image}};
    for (const auto& [key, kind] : kLists) {
        const auto list = doc.find(key);
        if (list == doc.end() || !list->is_array()) continue;
        for (const nlohmann::json& item : *list) {
            if (!item.is_object()) continue;
            const auto uri = item.find("uri");
            if (uri == item.end() || !uri->is_string()) continue;
            const std::string u = gltf.file_string(*uri);
            if (u.rfind("data:", 0) == 0) continue;  // held in the file itself
            // Decoded as the glTF specification says; as written too, which is how Assimp opens it.
            out.add(path.parent_path(), uri_decoded(u), kind);
            out.add(path.parent_path(), u, kind);
        }
    }
}

/// The file's bytes, mapped read-only (an FBX may be gigabytes: nothing is copied).
class MappedFile {
public:
    explicit MappedFile(const fs::path& path) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) return;
        struct stat st {};
        if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
            void* p = ::mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
            if (p != MAP_FAILED) {
                data_ = static_cast<const char*>(p);
                size_ = size_t(st.st_size);
            }
        }
        ::close(fd);
    }
    ~MappedFile() {
        if (data_) ::munmap(const_cast<char*>(data_), size_);
    }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    std::string_view bytes() const { return {data_ ? data_ : "", size_}; }

private:
    const char* data_ = nullptr;
    size_t size_ = 0;
};

/// The texture paths an FBX file holds: the strings of its `FileName`, `Filename` and
/// `RelativeFilename` properties (of Texture and Video objects). Binary FBX stores a property
/// as its name's length byte, the name, then an 'S' record: a 32-bit length and the bytes; ASCII
/// FBX writes `RelativeFilename: "path"`.
std::vector<std::string> fbx_file_names(std::string_view b) {
    std::vector<std::string> out;
    const bool binary = b.substr(0, 18) == "Kaydara FBX Binary";
    for (const std::string name : {"FileName", "Filename", "RelativeFilename"}) {
        const std::string marker = binary ? char(name.size()) + name + "S" : name + ": \"";
        for (size_t at = b.find(marker); at != std::string_view::npos; at = b.find(marker, at + 1)) {
            const size_t start = at + marker.size();
            size_t length = 0;
            if (binary) {
                if (start + 4 > b.size()) break;
                length = le32(reinterpret_cast<const unsigned char*>(b.data() + start));
                if (length > 4096 || start + 4 + length > b.size()) continue;
                out.emplace_back(b.substr(start + 4, length));
            } else {
                const size_t end = b.find('"', start);
                if (end == std::string_view::npos || end - start > 4096) continue;
                out.emplace_back(b.substr(start, end - start));
            }
        }
    }
    return out;
}

void add_fbx_files(const fs::path& path, SideFiles& out) {
    const MappedFile file(path);
    for (const std::string& name : fbx_file_names(file.bytes())) {
        out.add(path.parent_path(), name, MeshSideFile::Kind::MeshTexture);
        // A texture found beside the mesh by its file name alone, as readers fall back to.
        out.add(path.parent_path(), written_path(name).filename().string(), MeshSideFile::Kind::MeshTexture);
    }
}

}  // namespace

std::vector<MeshSideFile> mesh_side_files(const std::string& mesh_path) {
    SideFiles out;
    const fs::path path(mesh_path);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return {};
    const std::string ext = ascii_lower(path.extension().string());
    char magic[4] = {};
    std::ifstream(path, std::ios::binary).read(magic, 4);
    // The mesh loader's readers go by content where the extension's reader declines a file.
    if (ext == ".gltf" || ext == ".glb" || std::memcmp(magic, "glTF", 4) == 0)
        add_gltf_files(path, out);
    else if (ext == ".obj")
        add_obj_files(path, out);
    else if (ext == ".fbx")
        add_fbx_files(path, out);
    return out.take();
}

}  // namespace dp
