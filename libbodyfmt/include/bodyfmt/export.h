#pragma once
/// What libbodyfmt.so exports. The library is built with hidden visibility
/// (libbodyfmt/CMakeLists.txt), so that its YAML layer, its loader and every other internal
/// stay out of the shared library's symbol table, where another project could bind to them
/// and break at the next release. Every public header wraps its namespace as
///
///   #pragma GCC visibility push(default)
///   namespace bodyfmt {
///   ...
///   }  // namespace bodyfmt
///   #pragma GCC visibility pop
///
/// which exports everything declared there (functions, classes with their vtables and type
/// information) and nothing declared anywhere else, under GCC and clang alike: the pragma marks
/// each declaration, and its definition in a source file inherits the mark. (A visibility
/// attribute on the namespace does not do that under clang, which takes a function's visibility
/// from the namespace block its definition is in.) A test checks both sides
/// (tests/package/check_exports.sh). A declaration outside such a block can be exported alone
/// with `BODYFMT_API` in front of it.

#if defined(__GNUC__) || defined(__clang__)
#define BODYFMT_API [[gnu::visibility("default")]]
#else
#define BODYFMT_API
#endif
