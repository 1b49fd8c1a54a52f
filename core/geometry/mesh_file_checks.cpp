#include "geometry/mesh_file_checks.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>
#include <vector>

#include "base/error.h"
#include "base/text.h"
#include "geometry/gltf_json.h"
#include "geometry/mesh_limits.h"
#include "base/byte_order.h"

namespace dp {

namespace {

std::vector<char> read_prefix(const std::string& path, size_t max_bytes) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes(max_bytes);
    in.read(bytes.data(), std::streamsize(max_bytes));
    bytes.resize(size_t(in.gcount()));
    return bytes;
}

bool is_count(const std::string& s) {
    return !s.empty() && s.size() <= 19 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}


/// What the first characters of an MTL line make Assimp's reader do: start a material ("ne...",
/// either case of the n), write into the current one without checking there is one (a texture,
/// an anisotropy), or something harmless.
enum class MtlLine { Material, Unchecked, Other };

MtlLine mtl_line(const std::string& head) {
    if (head.size() >= 2 && (head[0] == 'n' || head[0] == 'N') && head[1] == 'e') return MtlLine::Material;
    if (head[0] == 'a' || head[0] == 'A') return MtlLine::Unchecked;
    const std::string key = ascii_lower(head.substr(0, 4));
    for (const char* texture : {"map_", "bump", "disp", "norm", "refl"})
        if (key == texture) return MtlLine::Unchecked;
    return MtlLine::Other;
}

bool starts_with(const std::vector<char>& bytes, std::initializer_list<unsigned char> mark) {
    return bytes.size() >= mark.size() && std::equal(mark.begin(), mark.end(), bytes.begin(), [](unsigned char m, char c) {
               return m == static_cast<unsigned char>(c);
           });
}

}  // namespace

void check_material_library(const std::string& path, const std::string& field) {
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    // A multiple of 4 bytes, so that the groups swapped below stay whole.
    std::vector<char> chunk(size_t(1) << 16);
    auto next_chunk = [&] {
        chunk.resize(size_t(1) << 16);
        in.read(chunk.data(), std::streamsize(chunk.size()));
        chunk.resize(size_t(in.gcount()));
    };
    next_chunk();
    if (ec || size < 8) return;  // Assimp refuses a file this small before reading it
    // The text as Assimp's reader sees it: a UTF-8 mark dropped, big-endian UTF-16 and UTF-32
    // byte-swapped (and left at that: their NUL bytes end lines).
    const size_t skip = starts_with(chunk, {0xEF, 0xBB, 0xBF}) ? 3 : 0;
    const size_t group = starts_with(chunk, {0x00, 0x00, 0xFE, 0xFF})            ? 4
                         : starts_with(chunk, {0xFE, 0xFF}) && size % 2 == 0 ? 2
                                                                                  : 1;
    std::string head;  // the current line's first characters
    uint64_t line = 1;
    for (size_t from = skip; !chunk.empty(); from = 0, next_chunk()) {
        for (size_t g = 0; g + group <= chunk.size(); g += group) std::reverse(&chunk[g], &chunk[g] + group);
        for (size_t i = from; i < chunk.size(); ++i) {
            const char c = chunk[i];
            if (c == '\n' || c == '\r' || c == '\f' || c == '\0') {
                line += c == '\n';
                head.clear();
                continue;
            }
            if (head.size() >= 4) continue;
            head += c;
            const MtlLine kind = mtl_line(head);
            if (kind == MtlLine::Material) return;
            if (kind == MtlLine::Unchecked)
                throw InputError(path, field,
                                 "material library: line " + std::to_string(line) + " ('" + head +
                                     "...') sets a material before the file's first one (newmtl)");
        }
    }
}

void check_ply_header(const std::string& path, const std::string& field) {
    constexpr size_t kMaxHeader = 64 * 1024;
    const std::vector<char> bytes = read_prefix(path, kMaxHeader);
    std::istringstream header(std::string(bytes.begin(), bytes.end()));
    static const std::set<std::string> kTypes = {"char",  "uchar",  "short", "ushort", "int",    "uint",
                                                 "float", "double", "int8",  "uint8",  "int16",  "uint16",
                                                 "int32", "uint32", "float32", "float64"};
    auto fail = [&](int line, const std::string& why) {
        throw InputError(path, field, "malformed PLY header, line " + std::to_string(line) + ": " + why);
    };
    std::string line;
    int n = 0;
    bool have_format = false, have_element = false;
    while (std::getline(header, line)) {
        ++n;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string word; words >> word;) w.push_back(word);
        if (n == 1) {
            if (line != "ply") fail(1, "the file does not start with \"ply\"");
            continue;
        }
        if (w.empty()) fail(n, "an empty line");
        const std::string& key = w[0];
        if (key == "end_header") {
            if (!have_format) fail(n, "no format line before end_header");
            if (!have_element) fail(n, "no element before end_header");
            return;
        }
        if (key == "comment" || key == "obj_info") continue;
        if (key == "format") {
            if (w.size() != 3 || (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
                fail(n, "expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
            have_format = true;
        } else if (key == "element") {
            if (w.size() != 3 || !is_count(w[2])) fail(n, "expected \"element NAME COUNT\"");
            // Assimp allocates by the declared count: each face is a triangle at the least.
            if (w[1] == "face") check_mesh_triangles(path, field, std::stoull(w[2]), "faces (declared in its header)");
            have_element = true;
        } else if (key == "property") {
            if (!have_element) fail(n, "a property before any element");
            const bool list = w.size() == 5 && w[1] == "list" && kTypes.count(w[2]) && kTypes.count(w[3]);
            const bool scalar = w.size() == 3 && kTypes.count(w[1]);
            if (!list && !scalar) fail(n, "expected \"property TYPE NAME\" or \"property list TYPE TYPE NAME\"");
        } else {
            fail(n, "unknown keyword \"" + key.substr(0, 40) + "\"");
        }
    }
    fail(n, bytes.size() == kMaxHeader ? "no end_header in the first 64 KiB" : "no end_header line");
}

bool is_gltf_json(const std::string& path) { return parse_gltf_json(gltf_json_text(path)).doc.is_object(); }

void check_gltf_buffers(const std::string& path, const std::string& field) {
    using json = nlohmann::json;
    std::error_code ec;
    const uint64_t file_size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path, field, "cannot read mesh: " + ec.message());
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(file_size);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(file_size));
    auto fail = [&](const std::string& why) { throw InputError(path, field, "malformed glTF: " + why); };

    std::string text;
    uint64_t bin_chunk = 0;
    if (file_size >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
        if (file_size < 20) fail("a GLB file shorter than its header");
        if (le32(&bytes[8]) > file_size) fail("the GLB header declares more bytes than the file holds");
        const uint64_t json_len = le32(&bytes[12]);
        if (20 + json_len > file_size) fail("the JSON chunk runs past the end of the file");
        text.assign(reinterpret_cast<const char*>(&bytes[20]), json_len);
        const uint64_t next = 20 + json_len;
        if (next + 8 <= file_size) {
            bin_chunk = le32(&bytes[next]);
            if (next + 8 + bin_chunk > file_size) fail("the binary chunk runs past the end of the file");
        }
    } else {
        text.assign(bytes.begin(), bytes.end());
    }
    const GltfJson gltf = parse_gltf_json(text);
    const json& doc = gltf.doc;
    if (doc.is_discarded() || !doc.is_object()) return;  // Assimp names the syntax error
    const auto buffers = doc.find("buffers");
    if (buffers == doc.end() || !buffers->is_array()) return;
    for (size_t i = 0; i < buffers->size(); ++i) {
        const json& b = (*buffers)[i];
        if (!b.is_object()) fail("buffers[" + std::to_string(i) + "] is not an object");
        const auto len = b.find("byteLength");
        if (len == b.end() || !len->is_number_unsigned()) fail("buffers[" + std::to_string(i) + "] has no byteLength");
        const uint64_t declared = len->get<uint64_t>();
        uint64_t available = bin_chunk;
        const auto uri = b.find("uri");
        if (uri != b.end() && uri->is_string()) {
            const std::string u = gltf.file_string(*uri);
            if (u.rfind("data:", 0) == 0) {
                available = u.size() / 4 * 3 + 3;  // base64 holds 3 bytes per 4 characters
            } else {
                const auto file = std::filesystem::path(path).parent_path() / u;
                available = std::filesystem::file_size(file, ec);
                if (ec) continue;  // a missing buffer file is Assimp's to report
            }
        }
        if (declared > available) {
            fail("buffers[" + std::to_string(i) + "] declares " + std::to_string(declared) + " bytes but holds " +
                 std::to_string(available));
        }
    }
}

}  // namespace dp
