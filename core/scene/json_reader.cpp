#include "scene/json_reader.h"
#include "base/text.h"
#include "base/input_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>

namespace dp {
namespace {

using json = nlohmann::json;

std::string list(JsonReader::Keys names) {
    std::string s;
    for (std::string_view n : names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
}

/// Rejects repeated keys in one object, which nlohmann would otherwise resolve silently.
class DuplicateKeyCheck {
  public:
    explicit DuplicateKeyCheck(const JsonReader& r) : reader_(r) {}
    bool operator()(int, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
                stack_.push_back(Frame(false));
                break;
            case json::parse_event_t::array_start:
                stack_.push_back(Frame(true));
                break;
            case json::parse_event_t::key: {
                Frame& f = stack_.back();
                f.key = parsed.get<std::string>();
                if (!f.keys.insert(f.key).second) reader_.fail(path(), "duplicate key");
                break;
            }
            case json::parse_event_t::value:
                if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
                break;
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                stack_.pop_back();
                if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
                break;
        }
        return true;
    }

  private:
    struct Frame {
        explicit Frame(bool is_array) : array(is_array) {}
        bool array;
        size_t index = 0;
        std::string key;
        std::set<std::string> keys;
    };
    std::string path() const {
        std::string p;
        for (const Frame& f : stack_) p = f.array ? json_at(p, f.index) : json_join(p, f.key);
        return p;
    }
    const JsonReader& reader_;
    std::vector<Frame> stack_;
};

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string strip_prefix(const std::exception& e) {
    std::string what = e.what();
    if (auto pos = what.find("] "); pos != std::string::npos) what = what.substr(pos + 2);
    return what;
}

}  // namespace

std::string json_join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string json_at(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i) + "]";
}

std::string shortest_decimal(double v) {
    char buf[64];
    auto res = std::to_chars(buf, buf + sizeof(buf), v);
    if (float(v) == v) res = std::to_chars(buf, buf + sizeof(buf), float(v));
    return std::string(buf, res.ptr);
}

std::string JsonReader::read_file(const std::string& what) const {
    // A project is a few kB; 16 MB refuses /dev/zero-like inputs long before memory runs out.
    check_input_file(file_, "", "a " + what, 16u << 20);
    std::ifstream in(file_, std::ios::binary);
    if (!in) fail("", "cannot open the " + what);
    std::string text(std::istreambuf_iterator<char>(in), {});
    if (in.bad()) fail("", "cannot read the " + what);
    return text;
}

json JsonReader::parse(const std::string& text) const {
    try {
        return json::parse(text, DuplicateKeyCheck(*this));
    } catch (const json::parse_error& e) {
        fail("", "invalid JSON at byte " + std::to_string(e.byte) + ": " + strip_prefix(e));
    } catch (const json::out_of_range& e) {
        // A literal beyond the double range ("number overflow parsing '1e999'"): no position
        // is reported, so locate the quoted literal in the text.
        std::string what = strip_prefix(e), where;
        size_t q0 = what.find('\''), q1 = what.rfind('\'');
        if (q0 != std::string::npos && q1 > q0) {
            size_t byte = text.find(what.substr(q0 + 1, q1 - q0 - 1));
            if (byte != std::string::npos) where = " at byte " + std::to_string(byte + 1);
        }
        fail("", "invalid JSON" + where + ": " + what + " (numbers must be finite)");
    }
}

void JsonReader::object(const json& j, const std::string& path, Keys allowed,
                        const std::string& context) const {
    if (!j.is_object()) wrong_type(j, path, "an object");
    for (const auto& item : j.items()) {
        const std::string& key = item.key();
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        std::string msg = "unknown key '" + key + "'" + context;
        std::string_view best;
        size_t best_d = 3;  // suggest only close matches: typos, not different words
        for (std::string_view a : allowed) {
            size_t d = edit_distance(key, a);
            if (d < best_d) best_d = d, best = a;
        }
        if (!best.empty()) msg += "; did you mean '" + std::string(best) + "'?";
        fail(json_join(path, key), msg + " (valid keys: " + list(allowed) + ")");
    }
}

const json& JsonReader::required(const json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(json_join(path, key), "required field is missing");
    return *it;
}

double JsonReader::number(const json& j, const std::string& path) const {
    if (!j.is_number()) wrong_type(j, path, "a number");
    double d = j.get<double>();
    check(std::isfinite(d), path, "must be a finite number");
    return d;
}

float JsonReader::real(const json& j, const std::string& path) const {
    double d = number(j, path);
    check(std::isfinite(float(d)), path,
          "must be a finite number (" + shortest_decimal(d) + " is outside the float range)");
    return float(d);
}

int64_t JsonReader::integer(const json& j, const std::string& path, int64_t lo, int64_t hi) const {
    auto range = [&](const std::string& got) {
        std::string msg = "must be an integer in [" + std::to_string(lo) + ", ";
        msg += hi == std::numeric_limits<int64_t>::max() ? "inf)" : std::to_string(hi) + "]";
        fail(path, msg + " (got " + got + ")");
    };
    int64_t v = 0;
    if (j.is_number_unsigned()) {
        uint64_t u = j.get<uint64_t>();
        if (u > uint64_t(hi)) range(std::to_string(u));
        v = int64_t(u);
    } else if (j.is_number_integer()) {
        v = j.get<int64_t>();
    } else if (j.is_number_float()) {
        double d = number(j, path);
        if (d != std::floor(d)) fail(path, "must be an integer (got " + shortest_decimal(d) + ")");
        if (d < double(lo) || d > double(hi)) range(shortest_decimal(d));
        v = int64_t(d);
    } else {
        wrong_type(j, path, "an integer");
    }
    if (v < lo || v > hi) range(std::to_string(v));
    return v;
}

uint64_t JsonReader::unsigned_integer(const json& j, const std::string& path) const {
    if (j.is_number_unsigned()) return j.get<uint64_t>();
    return uint64_t(integer(j, path, 0, std::numeric_limits<int64_t>::max()));
}

std::string JsonReader::string(const json& j, const std::string& path, bool non_empty) const {
    if (!j.is_string()) wrong_type(j, path, "a string");
    std::string s = j.get<std::string>();
    check(!non_empty || !s.empty(), path, "must not be empty");
    return s;
}

bool JsonReader::boolean(const json& j, const std::string& path) const {
    if (!j.is_boolean()) wrong_type(j, path, "true or false");
    return j.get<bool>();
}

std::vector<float> JsonReader::numbers(const json& j, const std::string& path, size_t n) const {
    std::string want = "an array of " + std::to_string(n) + " numbers";
    if (!j.is_array()) wrong_type(j, path, want.c_str());
    check(j.size() == n, path,
          "expected " + std::to_string(n) + " numbers, got " + std::to_string(j.size()));
    std::vector<float> v;
    for (size_t i = 0; i < n; ++i) v.push_back(real(j[i], json_at(path, i)));
    return v;
}

vec3 JsonReader::vector3(const json& j, const std::string& path) const {
    auto v = numbers(j, path, 3);
    return vec3(v[0], v[1], v[2]);
}

vec3 JsonReader::positive3(const json& j, const std::string& path, size_t n) const {
    auto v = numbers(j, path, n);
    for (size_t i = 0; i < n; ++i)
        check(v[i] > 0, json_at(path, i), "must be > 0 (got " + shortest_decimal(v[i]) + ")");
    return n == 3 ? vec3(v[0], v[1], v[2]) : vec3(v[0], 1.0f, v[1]);
}

vec3 JsonReader::colour(const json& j, const std::string& path) const {
    vec3 c = vector3(j, path);
    for (int i = 0; i < 3; ++i)
        check(c[i] >= 0 && c[i] <= 1, json_at(path, size_t(i)),
              "must be in [0, 1] (got " + shortest_decimal(c[i]) + ")");
    return c;
}

}  // namespace dp
