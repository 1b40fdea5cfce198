#include "calibration/yaml_structure.hpp"

#include <cstddef>
#include <sstream>
#include <string_view>

#include "horopter/core/error.hpp"

namespace horopter::detail {

namespace {

[[noreturn]] void refuse(const std::string& path, std::size_t line, const std::string& what) {
  std::ostringstream message;
  message << "calibration file '" << path << "' line " << line << ": " << what
          << "; a calibration file is one YAML document whose top-level fields start in one "
             "column";
  throw Error(message.str());
}

}  // namespace

void checkOneYamlDocument(const std::string& text, const std::string& path) {
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos) {
    std::ostringstream message;
    message << "calibration file '" << path << "' holds a NUL byte (offset " << nul
            << "): not a text calibration";
    throw Error(message.str());
  }
  // Lines as OpenCV's reader sees them: split at '\n', each ending at its
  // first '\r' (OpenCV reads on from the next line there, "\r\n" included).
  bool begun = false;          // the first field has been seen
  std::size_t rootColumn = 0;  // its column
  std::size_t rootLine = 0;
  std::size_t documentEnd = 0;  // the line of a "..." seen, 0 if none
  std::size_t lineNumber = 0;
  for (std::size_t start = 0; start <= text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    line = line.substr(0, line.find('\r'));
    ++lineNumber;
    start = end + 1;

    const std::size_t column = line.find_first_not_of(' ');
    if (column == std::string_view::npos || line[column] == '#') continue;  // blank, comment
    const std::string_view content = line.substr(column);
    if (documentEnd != 0)
      refuse(path, lineNumber,
             "text after the document end '...' of line " + std::to_string(documentEnd));
    if (content.substr(0, 3) == "...") {
      // OpenCV takes any line that starts with "..." for the end and skips
      // those three characters, so what follows them on the line counts as
      // text after the end ("...-" hangs it as "...\n-" does).
      const std::size_t after = content.find_first_not_of(' ', 3);
      if (after != std::string_view::npos && content[after] != '#')
        refuse(path, lineNumber, "text after the document end '...' on its line");
      documentEnd = lineNumber;
      continue;
    }
    if (!begun) {
      // Directives and the document start come before the first field.
      if (content[0] == '%') continue;
      if (content.substr(0, 3) == "---") {
        const std::size_t after = content.find_first_not_of(' ', 3);
        if (after == std::string_view::npos || content[after] == '#') continue;
        begun = true;  // "--- key: value": the document starts on this line
        rootColumn = column + after;
        rootLine = lineNumber;
        continue;
      }
      begun = true;
      rootColumn = column;
      rootLine = lineNumber;
      continue;
    }
    if (content.substr(0, 3) == "---") refuse(path, lineNumber, "a second YAML document ('---')");
    if (column < rootColumn) {
      std::ostringstream what;
      what << "indented " << column << " spaces, less than the first field's " << rootColumn
           << " (line " << rootLine << ")";
      refuse(path, lineNumber, what.str());
    }
  }
}

}  // namespace horopter::detail
