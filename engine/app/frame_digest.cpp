// frameDigest: FNV-1a (images a word at a time) over what a frame's stages produced; see
// horopter/app/pipeline_builder.hpp.
#include <cstdio>
#include <cstring>

#include "horopter/app/pipeline_builder.hpp"

namespace horopter {

namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

void mix(std::uint64_t& h, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= kFnvPrime;
  }
}

template <typename T>
void mixValue(std::uint64_t& h, const T& value) {
  mix(h, &value, sizeof value);
}

// FNV-1a's step over 8-byte words, the tail byte by byte: a byte at a
// time cost 3 % of the whole pipeline's instructions (the run digests
// every frame). The digest only tells runs apart; it is not kept anywhere.
void mixWords(std::uint64_t& h, const unsigned char* p, std::size_t bytes) {
  std::size_t i = 0;
  for (; i + 8 <= bytes; i += 8) {
    std::uint64_t word;
    std::memcpy(&word, p + i, sizeof word);
    h ^= word;
    h *= kFnvPrime;
  }
  mix(h, p + i, bytes - i);
}

// Rows one by one: a view's padding is not part of the image.
void mixImage(std::uint64_t& h, const cv::Mat& image) {
  mixValue(h, image.rows);
  mixValue(h, image.cols);
  mixValue(h, image.type());
  const std::size_t rowBytes = image.cols * image.elemSize();
  for (int y = 0; y < image.rows; ++y)
    mixWords(h, image.ptr(y), rowBytes);
}

void mixPart(std::uint64_t& h, const PartState& part) {
  mixValue(h, part.tracked);
  mixValue(h, part.observed);
  // Positions are compared as they are, bit for bit: the stages are
  // deterministic, so any difference is a difference in the pipeline.
  for (float v : {part.image.x, part.image.y, part.rig.x, part.rig.y, part.rig.z}) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    mixValue(h, bits);
  }
}

}  // namespace

std::uint64_t frameDigest(const Frame& frame) {
  std::uint64_t h = kFnvOffset;
  mixValue(h, frame.index);
  mixImage(h, frame.disparity);
  mixImage(h, frame.mask);
  mixValue(h, frame.body.godfather);
  mixPart(h, frame.body.head);
  mixPart(h, frame.body.leftHand);
  mixPart(h, frame.body.rightHand);
  return h;
}

std::string digestText(std::uint64_t digest) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(digest));
  return hex;
}

std::uint64_t foldDigest(std::uint64_t runDigest, std::uint64_t frame) {
  std::uint64_t h = runDigest == 0 ? kFnvOffset : runDigest;
  mixValue(h, frame);
  return h;
}

}  // namespace horopter
