#pragma once
/// \file atomic_file.hpp
/// Output files written whole or not at all: the content goes to a temporary file in the target's
/// folder (".<name>.<random>.tmp"), which is renamed over the target only when writing succeeded; on
/// any failure the temporary file is removed and the target is left as it was. The same scheme as the
/// Python side (netshape._atomic.atomic_write).

#include <functional>
#include <ostream>
#include <string>

namespace netshape {

/// Write `path` atomically: `fill` writes the content to the stream it is given (binary when `binary`).
/// Throws std::invalid_argument naming `path` when it is empty or its folder does not exist,
/// netshape::Error when the file cannot be written; exceptions from `fill` pass through (nothing is
/// written then).
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill,
                           bool binary = true);

}  // namespace netshape
