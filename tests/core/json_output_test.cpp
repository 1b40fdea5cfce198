// support/: the JSON helper (one NaN -> null rule, nlohmann's escaping) and
// checked file output (a failed write names the file and the reason).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>

#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "json_text.hpp"

namespace horopter {
namespace {

using detail::Json;
using detail::jsonNumber;
using detail::jsonText;

TEST(JsonText, NotFiniteIsNull) {
  EXPECT_TRUE(jsonNumber(std::nan("")).is_null());
  EXPECT_TRUE(jsonNumber(std::numeric_limits<double>::infinity()).is_null());
  EXPECT_TRUE(jsonNumber(-std::numeric_limits<double>::infinity(), 3).is_null());
  const Json j{{"a", jsonNumber(std::nan(""))}, {"b", jsonNumber(1.5)}};
  EXPECT_EQ(jsonText(j), "{\"a\":null,\"b\":1.5}");
  // Never a bare nan or inf, even for a NaN that reached a document unwrapped.
  EXPECT_EQ(jsonText(Json{{"c", std::nan("")}}), "{\"c\":null}");
}

TEST(JsonText, RoundsToTheDecimalsAsked) {
  EXPECT_EQ(jsonText(jsonNumber(1.23456, 3)), "1.235");
  EXPECT_EQ(jsonText(jsonNumber(0.2, 4)), "0.2");
  EXPECT_EQ(jsonText(jsonNumber(1e300, 3)), jsonText(Json(1e300)));  // too big to scale: as is
  EXPECT_DOUBLE_EQ(jsonNumber(0.1234567).get<double>(), 0.1234567);  // no decimals: as is
}

TEST(JsonText, EscapesQuotesBackslashesAndControlCharacters) {
  const std::string raw = std::string("say \"hi\" C:\\dir\nnext\tcol") + '\x01' + '\x1f';
  const std::string text = jsonText(Json{{"s", raw}});
  EXPECT_EQ(text, "{\"s\":\"say \\\"hi\\\" C:\\\\dir\\nnext\\tcol\\u0001\\u001f\"}");
  EXPECT_EQ(Json::parse(text).at("s").get<std::string>(), raw);  // and reads back the same
  EXPECT_EQ(text.find('\n'), std::string::npos);                 // one line
}

TEST(JsonText, BytesThatAreNotUtf8AreReplacedNotThrown) {
  const std::string text = jsonText(Json{{"name", std::string("cam\xff")}});
  EXPECT_EQ(text, "{\"name\":\"cam\xEF\xBF\xBD\"}");
}

TEST(JsonText, KeysKeepTheirOrder) {
  Json j;
  j["zeta"] = 1;
  j["alpha"] = 2;
  EXPECT_EQ(jsonText(j), "{\"zeta\":1,\"alpha\":2}");
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no horopter::Error)";
}

TEST(FileOutput, WritesTheBytes) {
  const std::string path = ::testing::TempDir() + "/horopter_file_output.txt";
  detail::writeFile(path, std::string("a\0b\n", 4), "test file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), std::string("a\0b\n", 4));
  std::filesystem::remove(path);
}

TEST(FileOutput, AMissingFolderNamesTheFileAndTheReason) {
  const std::string m =
      messageOf([] { detail::writeFile("/nonexistent-dir/x.json", "{}", "run summary"); });
  EXPECT_NE(m.find("cannot write the run summary '/nonexistent-dir/x.json'"), std::string::npos)
      << m;
  EXPECT_NE(m.find("No such file or directory"), std::string::npos) << m;
}

TEST(FileOutput, AFullDiskIsAnError) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  // /dev/full takes the open and fails every write with ENOSPC: the bytes
  // sit in the buffer until the flush, which is checked.
  const std::string m = messageOf([] { detail::writeFile("/dev/full", "{}\n", "trace"); });
  EXPECT_NE(m.find("cannot write the trace '/dev/full': No space left on device"),
            std::string::npos)
      << m;
  std::ofstream log("/dev/full");
  ASSERT_TRUE(log.is_open());
  log << "{\"t\":0}\n";
  const std::string s = messageOf([&] { detail::checkStream(log, "/dev/full", "telemetry log"); });
  EXPECT_NE(s.find("cannot write the telemetry log '/dev/full': No space left on device"),
            std::string::npos)
      << s;
}

}  // namespace
}  // namespace horopter
