// Strict JSON reading with locations: every error names the file, the JSON Pointer of the value
// ("/detail_types/2/candidates/count") and the reason, and unknown keys are errors rather than silently
// ignored (a typo like "tile_sise_m" must not fall back to a default without telling anyone).
#pragma once

#include <cmath>
#include <set>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace ug {

class JsonReader {
public:
    JsonReader(std::string source, std::string* error) : source_(std::move(source)), error_(error) {}

    // All return false after recording the first error; later calls keep the first message.
    bool fail(const std::string& pointer, const std::string& reason) {
        if (ok_) *error_ = source_ + ": " + (pointer.empty() ? "/" : pointer) + ": " + reason;
        ok_ = false;
        return false;
    }
    bool ok() const { return ok_; }

    bool expectObject(const nlohmann::json& j, const std::string& pointer) {
        return j.is_object() || fail(pointer, "expected an object, got " + typeName(j));
    }
    bool expectArray(const nlohmann::json& j, const std::string& pointer) {
        return j.is_array() || fail(pointer, "expected an array, got " + typeName(j));
    }
    // Fails on keys outside `allowed`.
    bool onlyKeys(const nlohmann::json& j, const std::string& pointer, const std::set<std::string>& allowed) {
        for (auto it = j.begin(); it != j.end(); ++it)
            if (!allowed.count(it.key())) return fail(pointer + "/" + it.key(), "unknown field");
        return true;
    }

    // Optional members: absent keeps *out. Present with the wrong type or out of range fails.
    bool number(const nlohmann::json& obj, const std::string& pointer, const char* key, float* out, double lo,
                double hi) {
        double v = *out;
        if (!number(obj, pointer, key, &v, lo, hi)) return false;
        *out = float(v);
        return true;
    }
    bool number(const nlohmann::json& obj, const std::string& pointer, const char* key, double* out, double lo,
                double hi) {
        auto it = obj.find(key);
        if (it == obj.end()) return true;
        const std::string p = pointer + "/" + key;
        if (!it->is_number()) return fail(p, "expected a number, got " + typeName(*it));
        double v = it->get<double>();
        if (!std::isfinite(v)) return fail(p, "not a finite number");
        if (v < lo || v > hi) return fail(p, formatRange(v, lo, hi));
        *out = v;
        return true;
    }
    template <typename U>
    bool integer(const nlohmann::json& obj, const std::string& pointer, const char* key, U* out, uint64_t lo,
                 uint64_t hi) {
        auto it = obj.find(key);
        if (it == obj.end()) return true;
        const std::string p = pointer + "/" + key;
        if (!it->is_number_integer()) return fail(p, "expected a non-negative integer, got " + typeName(*it));
        if (!it->is_number_unsigned()) return fail(p, "expected a non-negative integer, got a negative one");
        uint64_t v = it->get<uint64_t>();
        if (v < lo || v > hi) return fail(p, formatRange(double(v), double(lo), double(hi)));
        *out = U(v);
        return true;
    }
    // [x, y, z], each finite and within ±max_abs.
    bool vec3(const nlohmann::json& obj, const std::string& pointer, const char* key, glm::vec3* out,
              double max_abs) {
        auto it = obj.find(key);
        if (it == obj.end()) return true;
        const std::string p = pointer + "/" + key;
        if (!it->is_array() || it->size() != 3) return fail(p, "expected [x, y, z]");
        for (int a = 0; a < 3; ++a) {
            const nlohmann::json& v = (*it)[size_t(a)];
            if (!v.is_number()) return fail(p + "/" + std::to_string(a), "expected a number");
            const double x = v.get<double>();
            if (!std::isfinite(x) || std::fabs(x) > max_abs)
                return fail(p + "/" + std::to_string(a), "not a finite coordinate");
            (*out)[a] = float(x);
        }
        return true;
    }
    bool boolean(const nlohmann::json& obj, const std::string& pointer, const char* key, bool* out) {
        auto it = obj.find(key);
        if (it == obj.end()) return true;
        if (!it->is_boolean()) return fail(pointer + "/" + key, "expected true or false, got " + typeName(*it));
        *out = it->get<bool>();
        return true;
    }
    bool string(const nlohmann::json& obj, const std::string& pointer, const char* key, std::string* out,
                bool required = false) {
        auto it = obj.find(key);
        if (it == obj.end()) return !required || fail(pointer + "/" + key, "missing (required)");
        if (!it->is_string()) return fail(pointer + "/" + key, "expected a string, got " + typeName(*it));
        *out = it->get<std::string>();
        return true;
    }
    bool require(const nlohmann::json& obj, const std::string& pointer, const char* key) {
        return obj.contains(key) || fail(pointer + "/" + key, "missing (required)");
    }

    static std::string typeName(const nlohmann::json& j) {
        if (j.is_number_integer()) return "an integer";
        if (j.is_number()) return "a number";
        if (j.is_string()) return "a string";
        if (j.is_boolean()) return "a boolean";
        if (j.is_null()) return "null";
        if (j.is_array()) return "an array";
        return "an object";
    }

private:
    static std::string formatRange(double v, double lo, double hi) {
        char buf[160];
        std::snprintf(buf, sizeof(buf), "%g is out of range [%g, %g]", v, lo, hi);
        return buf;
    }
    std::string source_;
    std::string* error_;
    bool ok_ = true;
};

}  // namespace ug
