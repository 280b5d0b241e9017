// Reading an input file whole, with the checks every reader needs: it must be a regular
// file (not a folder, a FIFO or /dev/zero, which would be read until memory runs out) and
// no larger than a stated size. One YAML text must hold one document.
#pragma once

#include <cstdint>
#include <string>

namespace ddafit::io {

// Largest input file read: scenes, studies, CSV polylines. A 3000-block meshed scene
// is about 1 MB; 64 MB is far beyond any real input and well inside memory.
constexpr std::uintmax_t kMaxInputBytes = 64ull << 20;

// The text of `path`, or an empty string and `problem` set to one line naming the file
// and what is wrong with it.
std::string read_input_file(const std::string& path, std::string& problem,
                            std::uintmax_t max_bytes = kMaxInputBytes);

// Number of YAML documents in `text` that carry content: a `---` line starts another
// document, which yaml-cpp's Load() drops without a word. Read from the document markers
// (`---` or `...` at the start of a line, where YAML allows nothing else), not with
// YAML::LoadAll, which fuzzing sent into an endless loop (yaml-cpp 0.7).
int yaml_document_count(const std::string& text);

}  // namespace ddafit::io
