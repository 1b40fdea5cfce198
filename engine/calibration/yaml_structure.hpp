// A check of a YAML calibration's layout before OpenCV's reader sees it.
// OpenCV 4.6's YAML parser (cv::FileStorage) loops forever on some text
// after the end of its first document: once the first document ends, it
// skips three characters as if they were a "---" or "..." marker, and a '-'
// that is not "---" where it lands spins its directive loop without moving
// (found by tests/fuzz/calibration_file_fuzz.cpp; the smallest trigger,
// "%YAML:1.0\na: 1\n...\n-\n", is a unit test). A calibration is one YAML
// document, so anything that would end the first document early is refused
// here, with the line, instead.
#pragma once

#include <string>

namespace horopter::detail {

// Throws horopter::Error naming `path` and the line when `text` (the file's
// bytes, YAML as OpenCV's reader takes it) holds a NUL byte, a "..."
// document end with more after it (on its line too), a second "---"
// document, or a line indented less than the first field (which ends
// OpenCV's top level there).
void checkOneYamlDocument(const std::string& text, const std::string& path);

}  // namespace horopter::detail
