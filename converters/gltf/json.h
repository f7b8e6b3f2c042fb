#pragma once
/// The small JSON model body2gltf needs to post-process assimp's glTF (see SUPPORT.md): a
/// value tree that keeps object keys in insertion order, a strict parser for the JSON assimp
/// writes, and a deterministic compact writer (shortest round-trip numbers, integers without a
/// fraction). Not a general-purpose library: no comments, no duplicate-key detection.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bodyfmt::gltf {

class Json {
 public:
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject, kRaw };
  using Array = std::vector<Json>;
  using Object = std::vector<std::pair<std::string, Json>>;

  Json() = default;
  Json(std::nullptr_t) {}
  Json(bool b) : kind_(Kind::kBool), bool_(b) {}
  Json(double d) : kind_(Kind::kNumber), number_(d) {}
  Json(int i) : kind_(Kind::kNumber), number_(i) {}
  Json(std::size_t i) : kind_(Kind::kNumber), number_(static_cast<double>(i)) {}
  Json(const char* s) : kind_(Kind::kString), string_(s) {}
  Json(std::string s) : kind_(Kind::kString), string_(std::move(s)) {}
  Json(Array a) : kind_(Kind::kArray), array_(std::move(a)) {}
  static Json object() {
    Json j;
    j.kind_ = Kind::kObject;
    return j;
  }
  static Json array() { return Json(Array{}); }
  /// Text that is already JSON (the caller's promise), written as it is by dump(): a node's
  /// extras, kept as text from the writer to the output.
  static Json raw(std::string text) {
    Json j;
    j.kind_ = Kind::kRaw;
    j.string_ = std::move(text);
    return j;
  }

  Kind kind() const { return kind_; }
  bool is_null() const { return kind_ == Kind::kNull; }
  bool is_number() const { return kind_ == Kind::kNumber; }
  bool is_string() const { return kind_ == Kind::kString; }
  bool is_array() const { return kind_ == Kind::kArray; }
  bool is_object() const { return kind_ == Kind::kObject; }

  double number() const { return number_; }
  int integer() const { return static_cast<int>(number_); }
  const std::string& string() const { return string_; }
  bool boolean() const { return bool_; }
  Array& items() { return array_; }
  const Array& items() const { return array_; }
  Object& members() { return object_; }
  const Object& members() const { return object_; }

  /// Object member or nullptr.
  Json* find(std::string_view key);
  const Json* find(std::string_view key) const;
  /// Object member, appended (null) when absent; turns a null into an object.
  Json& operator[](std::string_view key);
  /// Removes an object member if present.
  void erase(std::string_view key);
  /// Appends to an array (turns a null into an array).
  void push_back(Json value);

  /// Compact, deterministic text.
  std::string dump() const;
  /// Appends the compact text to `out`.
  void dump_to(std::string& out) const;
  /// Parses a complete JSON text; nullopt with `error` set on malformed input.
  static std::optional<Json> parse(std::string_view text, std::string* error = nullptr);

 private:
  Kind kind_ = Kind::kNull;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  Array array_;
  Object object_;
};

}  // namespace bodyfmt::gltf
