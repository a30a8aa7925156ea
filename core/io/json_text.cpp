#include "io/json_text.h"

#include <vector>

#include <nlohmann/json.hpp>

namespace glint {
namespace {

using nlohmann::json;

[[noreturn]] void malformed_at(size_t byte, const std::string& why) {
    throw JsonTextError("malformed JSON at byte " + std::to_string(byte) + ": " + why);
}

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1,
// column 10: " lead, which the byte offset replaces.
std::string reason_of(const json::exception& e) {
    std::string what = e.what();
    what.erase(0, what.find("] ") + 2);
    if (what.starts_with("parse error")) what.erase(0, what.find(": ") + 2);
    return what;
}

// Builds the document from nlohmann's SAX events, as its own parser does, but with the depth
// bounded as containers open, and with the offset of every error: nlohmann's DOM parser
// reports a number beyond double's range (1e999) as out_of_range, without any position.
class BoundedDocument final : public json::json_sax_t {
public:
    json root;

    bool null() override { return add(nullptr); }
    bool boolean(bool v) override { return add(v); }
    bool number_integer(number_integer_t v) override { return add(v); }
    bool number_unsigned(number_unsigned_t v) override { return add(v); }
    bool number_float(number_float_t v, const string_t&) override { return add(v); }
    bool string(string_t& v) override { return add(std::move(v)); }
    bool binary(binary_t& v) override { return add(json::binary(std::move(v))); }  // not in JSON text
    bool start_object(std::size_t) override { return open(json::object()); }
    bool key(string_t& k) override {
        member_ = &(*open_.back())[k];  // a repeated key keeps its last value, as nlohmann does
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(json::array()); }
    bool end_array() override { return close(); }
    // `byte` is the parse_error's own byte, and the lexer's position for out_of_range.
    bool parse_error(std::size_t byte, const std::string&, const json::exception& e) override {
        malformed_at(byte, reason_of(e));
    }

private:
    // Places v in the open container (or as the root) and returns where it now lives. The
    // address stays valid while v is the container's last element, which it is while open.
    json* place(json v) {
        if (open_.empty()) return &(root = std::move(v));
        if (open_.back()->is_array()) {
            open_.back()->push_back(std::move(v));
            return &open_.back()->back();
        }
        *member_ = std::move(v);
        return member_;
    }
    bool add(json v) {
        place(std::move(v));
        return true;
    }
    bool open(json container) {
        if (open_.size() == size_t(kMaxJsonDepth))
            throw JsonTextError("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        open_.push_back(place(std::move(container)));
        return true;
    }
    bool close() {
        open_.pop_back();
        return true;
    }

    std::vector<json*> open_;  // the containers not yet closed, outermost first
    json* member_ = nullptr;   // where the open object's current key's value goes
};

}  // namespace

nlohmann::json parse_json_text(const std::string& text) {
    // nlohmann's lexer takes a NUL byte outside a string for the end of the input, so "{}\0..."
    // would parse as "{}" and hide what follows; JSON text has no NUL byte anywhere.
    if (const size_t nul = text.find('\0'); nul != std::string::npos) malformed_at(nul + 1, "NUL byte");
    BoundedDocument document;
    json::sax_parse(text, &document);  // strict: only whitespace may follow the value
    return std::move(document.root);
}

}  // namespace glint
