#pragma once
/// `file://` URIs (RFC 8089) and the paths the loader names files by.

#include <optional>
#include <string>

namespace bodyfmt::lsp {

/// The absolute path of a `file://` URI (percent-decoded, with no host or "localhost"), or
/// nullopt for any other URI (untitled:, https:, a remote host, a NUL byte).
std::optional<std::string> path_from_uri(const std::string& uri);

/// The `file://` URI of an absolute path; a relative path is made absolute first.
std::string uri_from_path(const std::string& path);

}  // namespace bodyfmt::lsp
