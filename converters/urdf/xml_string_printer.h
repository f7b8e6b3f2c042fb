#pragma once
/// A tinyxml2 printer that appends to a std::string the caller owns, so that a large document
/// can be printed piece by piece (each element tree printed, then deleted from its document)
/// into the one string that becomes the output file, with no printer buffer and no copy.
#include <tinyxml2.h>

#include <cstddef>
#include <string>

namespace bodyfmt::urdf {

class XmlStringPrinter : public tinyxml2::XMLPrinter {
 public:
  /// Appends to `out` until redirected.
  explicit XmlStringPrinter(std::string& out) : out_(&out) {}

  /// Appends to `out` from now on. The printer's state (depth, open elements) is kept, so
  /// text printed there fits at the same place in the document.
  void redirect(std::string& out) { out_ = &out; }

 protected:
  void Print(const char* format, ...) override;
  void Write(const char* data, std::size_t size) override { out_->append(data, size); }
  void Putc(char ch) override { out_->push_back(ch); }

 private:
  std::string* out_;
};

}  // namespace bodyfmt::urdf
