// The frame decoder (protocol/wire/frame_codec.*) against protobuf's own varint reader. The
// input's first byte sets the largest frame (1 byte to 8 MiB), its second seeds the sizes of
// the chunks the rest is fed in, as reads off a socket would cut it. The decoder must give the
// same frames, and end the same way (waiting for more, a frame too large with its announced
// length, a bad prefix), as protobuf's CodedInputStream reading the stream whole; after a
// fatal error it stays failed. Every frame that parses as a ClientMessage is written again
// (message_codec) and must decode and parse to the same message.

#include <random>
#include <string>
#include <vector>

#include <google/protobuf/io/coded_stream.h>

#include "felt/v1/envelope.pb.h"
#include "fuzz_target.hpp"
#include "wire/frame_codec.hpp"
#include "wire/message_codec.hpp"

namespace felt::fuzz {
namespace {

using wire::DecodeStatus;

struct Decoded {
  std::vector<std::string> frames;
  DecodeStatus end = DecodeStatus::kNeedMore;
  std::uint64_t announced_length = 0;  ///< with kTooLarge
  std::size_t left_over = 0;           ///< bytes after the last frame, with kNeedMore
};

/// The stream read whole by protobuf's varint reader.
Decoded reference(std::string_view stream, std::size_t max_frame_bytes) {
  Decoded out;
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(stream.data());
  google::protobuf::io::CodedInputStream in(bytes, static_cast<int>(stream.size()));
  for (;;) {
    const auto start = static_cast<std::size_t>(in.CurrentPosition());
    const std::size_t remaining = stream.size() - start;
    std::uint64_t length = 0;
    if (remaining == 0) break;
    if (!in.ReadVarint64(&length)) {
      // protobuf gives up after 10 bytes; fewer than that may be a prefix cut short
      if (remaining >= wire::kMaxVarintBytes)
        out.end = DecodeStatus::kBadPrefix;
      else
        out.left_over = remaining;
      return out;
    }
    if (length > max_frame_bytes) {
      out.end = DecodeStatus::kTooLarge;
      out.announced_length = length;
      return out;
    }
    const auto prefix = static_cast<std::size_t>(in.CurrentPosition()) - start;
    if (remaining - prefix < length) {
      out.left_over = remaining;
      return out;
    }
    out.frames.emplace_back(stream.substr(start + prefix, length));
    in.Skip(static_cast<int>(length));
  }
  return out;
}

/// The stream fed to the FrameDecoder in chunks of random sizes.
Decoded chunked(std::string_view stream, std::size_t max_frame_bytes, std::uint8_t seed) {
  Decoded out;
  wire::FrameDecoder decoder(max_frame_bytes);
  std::minstd_rand rng(seed + 1u);
  const std::size_t largest_chunk = std::size_t{1} << (seed % 12);
  std::size_t fed = 0;
  for (;;) {
    const wire::DecodeResult result = decoder.next();
    if (result.status == DecodeStatus::kFrame) {
      out.frames.emplace_back(reinterpret_cast<const char*>(result.payload.data()),
                              result.payload.size());
      continue;
    }
    if (result.status != DecodeStatus::kNeedMore) {
      out.end = result.status;
      out.announced_length = result.announced_length;
      decoder.feed(stream.substr(fed));
      check(decoder.next().status == result.status, "a failed decoder stays failed");
      return out;
    }
    if (fed == stream.size()) break;
    const std::size_t chunk = std::min<std::size_t>(1 + rng() % largest_chunk, stream.size() - fed);
    decoder.feed(stream.substr(fed, chunk));
    fed += chunk;
  }
  out.left_over = decoder.buffered();
  return out;
}

/// A frame that is a ClientMessage, written again, decodes and parses to the same message.
void check_round_trip(const std::string& payload) {
  v1::ClientMessage message;
  if (!message.ParseFromString(payload)) return;
  std::string framed;
  wire::append_message(framed, message);
  wire::FrameDecoder decoder(framed.size());
  decoder.feed(framed);
  const wire::DecodeResult again = decoder.next();
  check(again.status == DecodeStatus::kFrame && decoder.buffered() == 0,
        "a written message decodes as one frame");
  v1::ClientMessage parsed;
  check(wire::parse_message(again.payload, parsed), "a written message parses");
  check(parsed.SerializeAsString() == message.SerializeAsString(),
        "a written message parses to the same message");
}

}  // namespace
}  // namespace felt::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace felt::fuzz;
  if (size < 2) return 0;
  const std::size_t max_frame_bytes = std::size_t{1} << (data[0] % 24);
  const std::string_view stream = as_text(data + 2, size - 2);
  const Decoded expected = reference(stream, max_frame_bytes);
  const Decoded got = chunked(stream, max_frame_bytes, data[1]);
  check(got.frames == expected.frames, "the same frames as protobuf's reader");
  check(got.end == expected.end, "the same end as protobuf's reader");
  check(got.announced_length == expected.announced_length, "the same announced length");
  if (got.end == felt::wire::DecodeStatus::kNeedMore) {
    check(got.left_over == expected.left_over, "the same bytes left over");
  }
  for (std::size_t i = 0; i < got.frames.size() && i < 64; ++i) check_round_trip(got.frames[i]);
  return 0;
}
