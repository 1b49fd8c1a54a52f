#pragma once
// Validating access to a parsed JSON document: typed fields, unknown-key checks and parsing
// with duplicate-key rejection, every failure an InputError naming the file and the field's
// JSON path (e.g. "objects[2].material.type").
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/error.h"
#include "base/math.h"

namespace dp {

/// The JSON path of member `key` of the value at `path` ("a.b"; just `key` at the top level).
std::string json_join(const std::string& path, std::string_view key);
/// The JSON path of element `i` of the array at `path` ("a[3]").
std::string json_at(const std::string& path, size_t i);

/// Shortest decimal text that reads back as the same float (so 0.1f prints as 0.1), for
/// quoting numbers in messages.
std::string shortest_decimal(double v);

/// Validating accessors; every failure names the file and the JSON path of the field.
class JsonReader {
  public:
    using json = nlohmann::json;
    using Keys = std::initializer_list<std::string_view>;

    /// `file` only labels error messages.
    explicit JsonReader(std::string file) : file_(std::move(file)) {}

    /// Throws InputError for the reader's file and `field`.
    [[noreturn]] void fail(const std::string& field, const std::string& msg) const {
        throw InputError(file_, field, msg);
    }
    /// Fails with `msg` unless `ok`.
    void check(bool ok, const std::string& field, const std::string& msg) const {
        if (!ok) fail(field, msg);
    }
    /// Fails with "expected <want>, got <the JSON type of j>".
    [[noreturn]] void wrong_type(const json& j, const std::string& path, const char* want) const {
        fail(path, std::string("expected ") + want + ", got " + j.type_name());
    }

    /// The whole text of the reader's file; `what` names it in messages ("project file" gives
    /// "project file does not exist", "cannot read the project file"...).
    std::string read_file(const std::string& what) const;
    /// Parses `text`, rejecting repeated keys in one object (nlohmann would keep the last one
    /// silently). Invalid JSON and out-of-range numbers fail with the byte where they are.
    json parse(const std::string& text) const;

    /// Requires an object whose keys are all in `allowed`; `context` qualifies the message. An
    /// unknown key close to an allowed one (a typo) is answered with a suggestion.
    void object(const json& j, const std::string& path, Keys allowed,
                const std::string& context = "") const;

    /// Member `key` of `obj`; fails when it is missing.
    const json& required(const json& obj, const std::string& path, const char* key) const;
    /// Member `key` of `obj`, or nullptr.
    static const json* optional(const json& obj, const char* key) {
        auto it = obj.find(key);
        return it == obj.end() ? nullptr : &*it;
    }

    /// A finite number.
    double number(const json& j, const std::string& path) const;
    /// A finite number that is also finite as a float.
    float real(const json& j, const std::string& path) const;
    /// An integer in [lo, hi]; a float with an integral value (2e5) is accepted too.
    int64_t integer(const json& j, const std::string& path, int64_t lo, int64_t hi) const;
    /// A non-negative integer up to the full uint64_t range.
    uint64_t unsigned_integer(const json& j, const std::string& path) const;
    /// A string, non-empty unless `non_empty` is false.
    std::string string(const json& j, const std::string& path, bool non_empty = true) const;
    /// true or false.
    bool boolean(const json& j, const std::string& path) const;

    /// An array of exactly n finite numbers.
    std::vector<float> numbers(const json& j, const std::string& path, size_t n) const;
    /// An array of 3 finite numbers.
    vec3 vector3(const json& j, const std::string& path) const;
    /// Components must be strictly positive (sizes, scales). With n = 2 the array is [x, z] and
    /// y is 1 (a plane's size).
    vec3 positive3(const json& j, const std::string& path, size_t n = 3) const;
    /// RGB reflectance or transmittance: each component in [0, 1].
    vec3 colour(const json& j, const std::string& path) const;

    /// A string naming one of `options`; `what` names the kind in the message ("shape type").
    template <class E>
    E choice(const json& j, const std::string& path, const char* what,
             std::initializer_list<std::pair<std::string_view, E>> options) const {
        return choice_in<E>(j, path, what, options);
    }
    /// The same over a table of names (e.g. kShapeKinds).
    template <class E, size_t N>
    E choice(const json& j, const std::string& path, const char* what,
             const std::pair<const char*, E> (&options)[N]) const {
        return choice_in<E>(j, path, what, options);
    }

  private:
    template <class E, class Options>
    E choice_in(const json& j, const std::string& path, const char* what, const Options& options) const {
        std::string s = string(j, path);
        std::string valid;
        for (const auto& [name, value] : options) {
            if (name == s) return value;
            valid += (valid.empty() ? "" : ", ") + std::string(name);
        }
        fail(path, "unknown " + std::string(what) + " '" + s + "' (valid: " + valid + ")");
    }

    std::string file_;
};

}  // namespace dp
