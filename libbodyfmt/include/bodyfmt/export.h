#pragma once
/// BODYFMT_API: what libbodyfmt.so exports. The library is built with hidden visibility
/// (libbodyfmt/CMakeLists.txt), so that its YAML layer, its loader and every other internal
/// stay out of the shared library's symbol table, where another project could bind to them
/// and break at the next release. Every public header opens its namespace as
///
///   namespace BODYFMT_API bodyfmt {
///
/// which exports everything declared in that block (functions, classes with their vtables and
/// type information) and nothing declared anywhere else; a test checks both sides
/// (tests/package/check_exports.sh). A declaration outside such a block can be exported alone
/// with `BODYFMT_API` in front of it.

#if defined(__GNUC__) || defined(__clang__)
#define BODYFMT_API [[gnu::visibility("default")]]
#else
#define BODYFMT_API
#endif
