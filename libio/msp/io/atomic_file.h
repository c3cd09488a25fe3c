#pragma once
// Atomic file output: a file is written through a temporary in the same folder and renamed into
// place, so a reader never sees a half-written file and a failure leaves nothing behind.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace msp {

/// Calls `write` with a temporary path next to `path`, then renames the temporary to `path`;
/// if `write` throws, the temporary is removed and the exception passes on.
/// \throw ricci::IOError if the folder of `path` does not exist; whatever `write` throws.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);
/// Text, the same way. \throw ricci::IOError.
void write_text_atomically(const std::string& path, const std::string& text);
/// Binary bytes, the same way. \throw ricci::IOError.
void write_bytes_atomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

}  // namespace msp
