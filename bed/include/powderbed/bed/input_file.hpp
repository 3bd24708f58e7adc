#pragma once
// The checks every reader makes on an input file before it opens it, and the one way error
// messages quote what they read (docs/hardening.md "Every reader refuses what is not a file").
#include <cstddef>
#include <string>
#include <string_view>

namespace powderbed::bed {

// Throws InputError "<what>: '<path>' is a FIFO (accepted: a regular file)" when `path` exists
// and is not a regular file (a folder, a FIFO, a character or block device, a socket): opening a
// FIFO blocks until a writer comes and a device such as /dev/zero never ends, so a reader would
// hang or read until memory runs out. A path that does not exist is left to the caller, whose
// open names it. Symbolic links are followed.
void require_regular_file(const std::string& path, const std::string& what);

// `text` for a one-line message, in quotes: bytes that are not printable ASCII (line breaks,
// control bytes, the bytes of a binary file) are written as \xNN, and text beyond `max_chars`
// is cut with "...", so a binary or huge line cannot break the one-line promise.
std::string quoted_excerpt(std::string_view text, std::size_t max_chars = 80);

}  // namespace powderbed::bed
