#include "xml_string_printer.h"

#include <cstdarg>
#include <cstdio>

namespace bodyfmt::urdf {

void XmlStringPrinter::Print(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list again;
  va_copy(again, args);
  const int length = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  if (length > 0) {
    const std::size_t at = out_->size();
    out_->resize(at + static_cast<std::size_t>(length) + 1);  // vsnprintf writes a terminating NUL
    std::vsnprintf(&(*out_)[at], static_cast<std::size_t>(length) + 1, format, again);
    out_->resize(at + static_cast<std::size_t>(length));
  }
  va_end(again);
}

}  // namespace bodyfmt::urdf
