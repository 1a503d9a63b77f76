#include "scene/json_parse.h"

#include <vector>

namespace ug {

namespace {

using json = nlohmann::json;

// A SAX pass that builds nothing and only tracks where it is, so a failed parse can say which value broke.
// It runs only after the normal parse failed: the common path pays nothing for it.
class Locator : public nlohmann::json_sax<json> {
public:
    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        stack_.push_back({true, "", 0, false});
        return true;
    }
    bool key(string_t& k) override {
        stack_.back().key = k;
        stack_.back().has_key = true;
        return true;
    }
    bool end_object() override {
        stack_.pop_back();
        return value();
    }
    bool start_array(std::size_t) override {
        stack_.push_back({false, "", 0, false});
        return true;
    }
    bool end_array() override {
        stack_.pop_back();
        return value();
    }
    bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) override {
        position_ = position;
        token_ = token;
        id_ = e.id;
        what_ = e.what();
        // The failing value is the next one in the innermost container: an object's current key, or the
        // array's next index.
        pointer_ = pointer(true);
        return false;
    }

    std::size_t position_ = 0;
    std::string token_, what_, pointer_;
    int id_ = 0;

private:
    struct Level {
        bool object;
        std::string key;
        std::size_t index;  // arrays: values seen so far
        bool has_key;
    };
    // A value (scalar or a closed container) completes one element of the enclosing level.
    bool value() {
        if (!stack_.empty()) {
            Level& l = stack_.back();
            if (l.object) l.has_key = false;
            else ++l.index;
        }
        return true;
    }
    std::string pointer(bool pending) const {
        std::string p;
        for (size_t k = 0; k < stack_.size(); ++k) {
            const Level& l = stack_[k];
            const bool last = k + 1 == stack_.size();
            if (l.object) {
                if (!last || (pending && l.has_key)) p += "/" + escape(l.key);
            } else {
                // Inner levels point at the element being read, which is the index of the values seen.
                if (!last || pending) p += "/" + std::to_string(l.index);
            }
        }
        return p;
    }
    static std::string escape(const std::string& key) {  // RFC 6901: ~ -> ~0, / -> ~1
        std::string out;
        for (char c : key) {
            if (c == '~') out += "~0";
            else if (c == '/') out += "~1";
            else out += c;
        }
        return out;
    }
    std::vector<Level> stack_;
};

void lineAndColumn(const std::string& text, std::size_t position, std::size_t* line, std::size_t* column) {
    *line = 1;
    *column = 1;
    const std::size_t end = std::min(position, text.size());
    for (std::size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++*line;
            *column = 1;
        } else {
            ++*column;
        }
    }
}

}  // namespace

bool parseJsonText(const std::string& text, const std::string& source, json* out, std::string* error) {
    try {
        *out = json::parse(text);
        return true;
    } catch (const json::exception&) {
        // Fall through: locate it with a second pass below.
    }
    Locator locator;
    json::sax_parse(text, &locator, json::input_format_t::json, /*strict=*/true);
    std::size_t line = 0, column = 0;
    // The position is one past the last character read. A number that overflowed is reported at its
    // first character; a syntax error at the character that broke it (as nlohmann's own column does).
    const std::size_t read = locator.position_;
    const std::size_t start = locator.id_ == 406 && read >= locator.token_.size() ? read - locator.token_.size()
                                                                                  : (read > 0 ? read - 1 : 0);
    lineAndColumn(text, start, &line, &column);
    const std::string at = "line " + std::to_string(line) + ", column " + std::to_string(column);
    const std::string pointer = locator.pointer_.empty() ? std::string("/") : locator.pointer_;
    if (locator.id_ == 406) {
        // A value error like any other the reader reports: the place is the JSON Pointer.
        *error = source + ": " + pointer + ": number " + locator.token_ +
                 " is out of range (larger than a double can hold) (" + at + ")";
    } else {
        // nlohmann's own text is informative ("syntax error while parsing object key - unexpected ...");
        // drop its "[json.exception.parse_error.101] parse error at line 3, column 5: " prefix, we say it.
        std::string reason = locator.what_;
        const std::size_t colon = reason.find(": ");
        if (reason.rfind("[json.exception.", 0) == 0 && colon != std::string::npos) reason = reason.substr(colon + 2);
        *error = source + ": invalid JSON at " + at + " (in " + pointer + "): " + reason;
    }
    return false;
}

}  // namespace ug
