// fmt's compiled part, built into bodycheck and bodyinfo (tools/CMakeLists.txt,
// bodyfmt_static_runtime) in place of libfmt.so.
//
// Those two tools link the C++ runtime statically: on a single robot most of their run is
// process start-up, and binding libstdc++'s symbols was a quarter of it (issue 14). libfmt.so
// would load the shared runtime anyway, so fmt comes in as code. format-inl.h defines fmt's
// out-of-line functions when FMT_HEADER_ONLY is not set; the templates that format.h declares
// `extern` are instantiated here for `char`, the only character type the tools format.

#include <fmt/format-inl.h>

#if FMT_VERSION < 90000 || FMT_VERSION >= 100000
#error "written against fmt 9 (Debian 12); tools/CMakeLists.txt only builds it for that version"
#endif

FMT_BEGIN_NAMESPACE
namespace detail {
template FMT_API auto thousands_sep_impl(locale_ref) -> thousands_sep_result<char>;
template FMT_API auto decimal_point_impl(locale_ref) -> char;
}  // namespace detail
FMT_END_NAMESPACE
