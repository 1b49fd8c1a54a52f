#pragma once
// A glTF file's JSON as Assimp's glTF readers take it (internal to core/geometry): the checks
// before Assimp reads a file and the list of the files it names must see the document Assimp sees.
#include <string>

#include <nlohmann/json.hpp>

namespace dp {

/// The JSON text of a .gltf file, or of a .glb file's first chunk ("" where that chunk runs past
/// the file's end).
std::string gltf_json_text(const std::string& path);

/// A glTF document. Assimp's JSON parser does not check UTF-8, so text that nlohmann refuses for
/// its encoding is parsed again with its bytes 0x80 and up read as Latin-1 characters;
/// `file_string` turns a string of such a document back into the file's bytes (a URI names the
/// file whose name has those bytes).
struct GltfJson {
    nlohmann::json doc;  ///< discarded where the text is no JSON either way
    bool latin1 = false;
    std::string file_string(const nlohmann::json& value) const;
};
GltfJson parse_gltf_json(const std::string& text);

}  // namespace dp
