// JSON documents through nlohmann/json: the one place that says how a number
// that is not finite is written, and how a document becomes text. Every JSON
// the tool and the library write (run summary, trace, telemetry, the CLI's
// --json reports) goes through here, so escaping is nlohmann's (quotes,
// backslashes, control characters) and no bare nan or inf reaches a reader.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace horopter::detail {

// Keys stay in the order they are set, as the documents were always written.
using Json = nlohmann::ordered_json;

// `v` as a JSON value: null when it is not finite (NaN, +-inf: no JSON reader
// takes them), else `v`, rounded to `decimals` places when decimals >= 0
// (times to the microsecond: jsonNumber(ms, 3)).
Json jsonNumber(double v, int decimals = -1);

// The document as one line of compact text (no spaces, no newline). Bytes
// that are not UTF-8 (a device's name, a fault message) become U+FFFD
// instead of throwing.
std::string jsonText(const Json& document);

}  // namespace horopter::detail
