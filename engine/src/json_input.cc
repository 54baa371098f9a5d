#include "idbench/engine/json_input.h"

#include <stdexcept>
#include <unordered_set>
#include <vector>

#include "idbench/engine/printable_text.h"

namespace idbench {
namespace {

using json = nlohmann::json;

// nlohmann's DOM builder behind a SAX handler of our own that checks the
// depth and the keys before each event is passed on. (nlohmann's parser
// callback sees the depth and keys as well, but its builder scans the
// enclosing array on every object's end: quadratic on [{}, {}, ...].)
class CheckedBuilder {
 public:
  CheckedBuilder(json* result, const std::string& source) : builder_(*result, /*allow_exceptions=*/true), source_(source) {}

  bool null() { return Element() && builder_.null(); }
  bool boolean(bool value) { return Element() && builder_.boolean(value); }
  bool number_integer(json::number_integer_t value) { return Element() && builder_.number_integer(value); }
  bool number_unsigned(json::number_unsigned_t value) { return Element() && builder_.number_unsigned(value); }
  bool number_float(json::number_float_t value, const json::string_t& text) {
    return Element() && builder_.number_float(value, text);
  }
  bool string(json::string_t& value) { return Element() && builder_.string(value); }
  bool binary(json::binary_t& value) { return Element() && builder_.binary(value); }
  bool start_object(std::size_t size) { return Open(true) && builder_.start_object(size); }
  bool key(json::string_t& key) {
    Level& object = levels_.back();
    object.key = key;
    if (!object.keys.insert(key).second) Fail("key repeated in one object (each key may be given once)");
    return builder_.key(key);
  }
  bool end_object() {
    levels_.pop_back();
    return builder_.end_object();
  }
  bool start_array(std::size_t size) { return Open(false) && builder_.start_array(size); }
  bool end_array() {
    levels_.pop_back();
    return builder_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    return builder_.parse_error(position, token, e);  // throws e
  }

 private:
  struct Level {
    bool object = false;
    std::string key;                       // object: the key being read
    long long index = -1;                  // array: the element being read
    std::unordered_set<std::string> keys;  // object: the keys so far
  };

  // A value starts: in an array, the next element.
  bool Element() {
    if (!levels_.empty() && !levels_.back().object) ++levels_.back().index;
    return true;
  }
  bool Open(bool object) {
    Element();
    if (levels_.size() >= static_cast<size_t>(kMaxJsonDepth)) {
      Fail("more than " + std::to_string(kMaxJsonDepth) + " nested arrays and objects");
    }
    levels_.push_back({object, {}, -1, {}});
    return true;
  }
  // "source: .files[1].path: what", each key cut at 64 bytes, the path at 120.
  [[noreturn]] void Fail(const std::string& what) const {
    std::string path;
    for (const Level& level : levels_) {
      path += level.object ? "." + PrintableText(level.key) : "[" + std::to_string(level.index) + "]";
    }
    throw std::invalid_argument(source_ + ": " + PrintableText(path, 120) + ": " + what);
  }

  nlohmann::detail::json_sax_dom_parser<json> builder_;
  const std::string& source_;
  std::vector<Level> levels_;
};

}  // namespace

json ParseJsonInput(const std::string& text, const std::string& source) {
  json result;
  CheckedBuilder builder(&result, source);
  try {
    json::sax_parse(text, &builder);
  } catch (const json::exception& e) {  // a syntax error, or a number out of range (1e999)
    std::string what = e.what();
    if (const size_t at = what.find("] "); what.starts_with("[json.exception.") && at != std::string::npos) {
      what = what.substr(at + 2);
    }
    throw std::invalid_argument(source + ": not valid JSON: " + PrintableText(what, 200));
  }
  return result;
}

}  // namespace idbench
