// FrameDecoder, append_frame and append_varint against hand-computed varints and a reference
// decoder written from the framing rules, plus the protobuf message layer on top.

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <gtest/gtest.h>

#include "felt/v1/envelope.pb.h"
#include "wire/frame_codec.hpp"
#include "wire/message_codec.hpp"

namespace felt::wire {
namespace {

std::string bytes(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) out.push_back(static_cast<char>(v));
  return out;
}

std::string varint(std::uint64_t value) {
  std::string out;
  append_varint(out, value);
  return out;
}

std::string_view as_view(std::span<const std::uint8_t> payload) {
  return {reinterpret_cast<const char*>(payload.data()), payload.size()};
}

// Payload sizes around the 1- and 2-byte varint boundaries, and one that needs 3 bytes.
const std::vector<std::size_t> kPayloadSizes = {0, 1, 127, 128, 300, 70000};

// Distinct pseudo-random contents, so a frame returned out of order or shifted is noticed.
std::vector<std::string> make_payloads() {
  std::mt19937 rng(1234);
  std::vector<std::string> payloads;
  for (std::size_t size : kPayloadSizes) {
    std::string p(size, '\0');
    for (char& c : p) c = static_cast<char>(rng() & 0xff);
    payloads.push_back(std::move(p));
  }
  return payloads;
}

std::string concatenated_frames(const std::vector<std::string>& payloads) {
  std::string stream;
  for (const std::string& p : payloads) append_frame(stream, p);
  return stream;
}

// Takes every whole frame now available, checking each against `expected` from `*taken` on.
// Returns false (after recording a failure) on anything but kFrame or kNeedMore.
bool drain(FrameDecoder& decoder, const std::vector<std::string>& expected, std::size_t* taken) {
  for (;;) {
    const DecodeResult r = decoder.next();
    if (r.status == DecodeStatus::kNeedMore) return true;
    if (r.status != DecodeStatus::kFrame) {
      ADD_FAILURE() << "unexpected status " << static_cast<int>(r.status);
      return false;
    }
    if (*taken >= expected.size()) {
      ADD_FAILURE() << "more frames than were sent";
      return false;
    }
    // compare before the next feed(): the span is only valid until then
    if (as_view(r.payload) != expected[*taken]) {
      ADD_FAILURE() << "frame " << *taken << " differs (size " << r.payload.size() << ", expected "
                    << expected[*taken].size() << ")";
      return false;
    }
    ++*taken;
  }
}

TEST(FrameCodec, VarintMatchesKnownEncodings) {
  EXPECT_EQ(varint(0), bytes({0x00}));
  EXPECT_EQ(varint(1), bytes({0x01}));
  EXPECT_EQ(varint(127), bytes({0x7f}));
  EXPECT_EQ(varint(128), bytes({0x80, 0x01}));
  EXPECT_EQ(varint(300), bytes({0xac, 0x02}));
  EXPECT_EQ(varint(16383), bytes({0xff, 0x7f}));
  EXPECT_EQ(varint(16384), bytes({0x80, 0x80, 0x01}));
  EXPECT_EQ(varint(std::uint64_t{1} << 32), bytes({0x80, 0x80, 0x80, 0x80, 0x10}));
  EXPECT_EQ(varint(0xffffffffu), bytes({0xff, 0xff, 0xff, 0xff, 0x0f}));
  EXPECT_EQ(varint(std::uint64_t{1} << 63),
            bytes({0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01}));
  EXPECT_EQ(varint(std::numeric_limits<std::uint64_t>::max()),
            bytes({0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x01}));
}

TEST(FrameCodec, VarintLengthIsCeilBitsOverSeven) {
  // a value with its highest set bit at position b takes ceil((b + 1) / 7) bytes
  for (int b = 0; b < 64; ++b) {
    const std::uint64_t value = std::uint64_t{1} << b;
    const std::string enc = varint(value);
    EXPECT_EQ(enc.size(), static_cast<std::size_t>(b / 7 + 1)) << "bit " << b;
    EXPECT_LE(enc.size(), kMaxVarintBytes);
    // continuation bit on every byte but the last
    for (std::size_t i = 0; i + 1 < enc.size(); ++i) {
      EXPECT_NE(static_cast<std::uint8_t>(enc[i]) & 0x80, 0) << "bit " << b;
    }
    EXPECT_EQ(static_cast<std::uint8_t>(enc.back()) & 0x80, 0) << "bit " << b;
  }
}

TEST(FrameCodec, AppendFrameIsVarintThenPayload) {
  std::string out = "x";  // appends, does not overwrite
  append_frame(out, std::string(300, 'a'));
  ASSERT_EQ(out.size(), 1u + 2u + 300u);
  EXPECT_EQ(out.substr(0, 3), "x" + bytes({0xac, 0x02}));
  EXPECT_EQ(out.substr(3), std::string(300, 'a'));

  std::string empty;
  append_frame(empty, "");
  EXPECT_EQ(empty, bytes({0x00}));
}

TEST(FrameCodec, AllFramesInOneRead) {
  const std::vector<std::string> payloads = make_payloads();
  const std::string stream = concatenated_frames(payloads);
  FrameDecoder decoder(100000);
  decoder.feed(stream);
  std::size_t taken = 0;
  ASSERT_TRUE(drain(decoder, payloads, &taken));
  EXPECT_EQ(taken, payloads.size());
  EXPECT_EQ(decoder.buffered(), 0u);
}

TEST(FrameCodec, SplitAtEveryByteBoundary) {
  const std::vector<std::string> payloads = make_payloads();
  const std::string stream = concatenated_frames(payloads);
  const std::string_view all(stream);
  for (std::size_t k = 0; k <= stream.size(); ++k) {
    FrameDecoder decoder(100000);
    std::size_t taken = 0;
    decoder.feed(all.substr(0, k));
    ASSERT_TRUE(drain(decoder, payloads, &taken)) << "split at " << k;
    EXPECT_LE(decoder.buffered(), k);
    decoder.feed(all.substr(k));
    ASSERT_TRUE(drain(decoder, payloads, &taken)) << "split at " << k;
    ASSERT_EQ(taken, payloads.size()) << "split at " << k;
    ASSERT_EQ(decoder.buffered(), 0u) << "split at " << k;
  }
}

TEST(FrameCodec, FirstFrameWalksFramesBackToBack) {
  const std::vector<std::string> payloads = make_payloads();
  const std::string stream = concatenated_frames(payloads);
  std::string_view rest(stream);
  for (const std::string& payload : payloads) {
    const std::optional<FrameView> frame = first_frame(rest);
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->payload, payload);
    rest.remove_prefix(frame->size);
  }
  EXPECT_TRUE(rest.empty());
}

TEST(FrameCodec, FirstFrameOfACutBufferIsNothing) {
  std::string stream;
  append_frame(stream, std::string(300, 'a'));
  for (std::size_t k = 0; k < stream.size(); ++k) {
    EXPECT_FALSE(first_frame(std::string_view(stream).substr(0, k))) << "cut at " << k;
  }
  EXPECT_FALSE(first_frame(std::string(11, '\xff')));  // no varint ends within 10 bytes
}

TEST(FrameCodec, OneByteAtATime) {
  const std::vector<std::string> payloads = make_payloads();
  const std::string stream = concatenated_frames(payloads);
  FrameDecoder decoder(100000);
  std::size_t taken = 0;
  for (char c : stream) {
    decoder.feed(std::string_view(&c, 1));
    ASSERT_TRUE(drain(decoder, payloads, &taken));
  }
  EXPECT_EQ(taken, payloads.size());
  EXPECT_EQ(decoder.buffered(), 0u);
}

TEST(FrameCodec, BufferedShrinksAsFramesAreTaken) {
  const std::vector<std::string> payloads = make_payloads();
  const std::string stream = concatenated_frames(payloads);
  FrameDecoder decoder(100000);
  EXPECT_EQ(decoder.buffered(), 0u);
  decoder.feed(stream);
  std::size_t remaining = stream.size();
  EXPECT_EQ(decoder.buffered(), remaining);
  for (const std::string& p : payloads) {
    const DecodeResult r = decoder.next();
    ASSERT_EQ(r.status, DecodeStatus::kFrame);
    remaining -= varint(p.size()).size() + p.size();
    EXPECT_EQ(decoder.buffered(), remaining);
  }
  EXPECT_EQ(decoder.next().status, DecodeStatus::kNeedMore);
  EXPECT_EQ(decoder.buffered(), 0u);
}

TEST(FrameCodec, PartialFrameIsKeptUntilComplete) {
  FrameDecoder decoder(1000);
  std::string frame;
  append_frame(frame, "hello");
  decoder.feed(std::string_view(frame).substr(0, 3));
  EXPECT_EQ(decoder.next().status, DecodeStatus::kNeedMore);
  EXPECT_EQ(decoder.buffered(), 3u);  // nothing taken from an incomplete frame
  decoder.feed(std::string_view(frame).substr(3));
  const DecodeResult r = decoder.next();
  ASSERT_EQ(r.status, DecodeStatus::kFrame);
  EXPECT_EQ(as_view(r.payload), "hello");
}

TEST(FrameCodec, FrameOfExactlyTheLimitIsAccepted) {
  FrameDecoder decoder(300);
  std::string frame;
  append_frame(frame, std::string(300, 'z'));
  decoder.feed(frame);
  const DecodeResult r = decoder.next();
  ASSERT_EQ(r.status, DecodeStatus::kFrame);
  EXPECT_EQ(r.payload.size(), 300u);
}

TEST(FrameCodec, OversizedPrefixIsTooLargeAndSticky) {
  FrameDecoder decoder(1000);
  std::string ok;
  append_frame(ok, "ok");
  decoder.feed(ok + varint(1001));  // one byte over the limit, payload never sent
  ASSERT_EQ(decoder.next().status, DecodeStatus::kFrame);
  const DecodeResult r = decoder.next();
  EXPECT_EQ(r.status, DecodeStatus::kTooLarge);
  EXPECT_EQ(r.announced_length, 1001u);
  EXPECT_TRUE(r.payload.empty());

  // a valid frame after the bad prefix must not resynchronise the stream
  std::string more;
  append_frame(more, "after");
  decoder.feed(more);
  decoder.feed(std::string(2000, 'x'));
  for (int i = 0; i < 3; ++i) {
    const DecodeResult again = decoder.next();
    EXPECT_EQ(again.status, DecodeStatus::kTooLarge);
    EXPECT_TRUE(again.payload.empty());
  }
}

TEST(FrameCodec, HugeAnnouncedLengthIsReportedWithoutAllocating) {
  FrameDecoder decoder(1 << 20);
  decoder.feed(varint(std::numeric_limits<std::uint64_t>::max()));
  const DecodeResult r = decoder.next();
  EXPECT_EQ(r.status, DecodeStatus::kTooLarge);
  EXPECT_EQ(r.announced_length, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(decoder.buffered(), 10u);  // only the received bytes are held

  FrameDecoder d32(1 << 20);
  d32.feed(varint(std::uint64_t{1} << 32));
  const DecodeResult r32 = d32.next();
  EXPECT_EQ(r32.status, DecodeStatus::kTooLarge);
  EXPECT_EQ(r32.announced_length, std::uint64_t{1} << 32);
}

TEST(FrameCodec, ElevenContinuationBytesAreBadPrefix) {
  FrameDecoder decoder(1000);
  decoder.feed(std::string(11, '\xff'));
  EXPECT_EQ(decoder.next().status, DecodeStatus::kBadPrefix);
  decoder.feed(bytes({0x01, 0x41}));
  EXPECT_EQ(decoder.next().status, DecodeStatus::kBadPrefix);
}

TEST(FrameCodec, IncompletePrefixNeedsMore) {
  // up to nine continuation bytes may still end in a valid 10-byte varint
  for (int n = 1; n <= 9; ++n) {
    FrameDecoder decoder(1000);
    decoder.feed(std::string(static_cast<std::size_t>(n), '\x80'));
    EXPECT_EQ(decoder.next().status, DecodeStatus::kNeedMore) << n;
  }
}

TEST(FrameCodec, NonMinimalVarintPrefixIsAccepted) {
  // 0x85 0x00 is a valid, if non-minimal, encoding of 5 that protobuf parsers accept
  FrameDecoder decoder(1000);
  decoder.feed(bytes({0x85, 0x00}) + "abcde");
  const DecodeResult r = decoder.next();
  ASSERT_EQ(r.status, DecodeStatus::kFrame);
  EXPECT_EQ(as_view(r.payload), "abcde");
}

// What a correct decoder must report for the bytes stream[pos...]: a reference written from the
// framing rules (at most 10 varint bytes, length <= limit), not from the implementation.
struct Expected {
  DecodeStatus status;
  std::size_t payload_begin = 0;
  std::size_t payload_size = 0;
  std::uint64_t announced = 0;
};

Expected reference_next(const std::string& stream, std::size_t pos, std::size_t limit) {
  std::uint64_t length = 0;
  std::size_t n = 0;
  for (;;) {
    if (n == 10) return {DecodeStatus::kBadPrefix};
    if (pos + n == stream.size()) return {DecodeStatus::kNeedMore};
    const auto byte = static_cast<std::uint8_t>(stream[pos + n]);
    length += static_cast<std::uint64_t>(byte & 0x7f) << (7 * n);
    ++n;
    if ((byte & 0x80) == 0) break;
  }
  if (length > limit) return {DecodeStatus::kTooLarge, 0, 0, length};
  if (stream.size() - (pos + n) < length) return {DecodeStatus::kNeedMore};
  return {DecodeStatus::kFrame, pos + n, static_cast<std::size_t>(length), 0};
}

TEST(FrameCodec, RandomGarbageMatchesReferenceDecoder) {
  std::mt19937 rng(20240521);
  constexpr std::size_t kLimit = 64;
  int frames_seen = 0;
  int failures_seen = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    // mostly small bytes so that some garbage parses as frames, some as long prefixes
    const std::size_t size = rng() % 400;
    std::string stream(size, '\0');
    const bool small = trial % 2 == 0;
    for (char& c : stream) {
      const std::uint32_t r = rng();
      c = static_cast<char>(small && r % 4 != 0 ? (r >> 8) % 80 : (r >> 8) & 0xff);
    }

    FrameDecoder decoder(kLimit);
    std::size_t fed = 0;
    std::size_t consumed = 0;  // where the reference says the next frame starts
    bool failed = false;
    while (!failed) {
      // random chunking, sometimes empty chunks
      const std::size_t chunk = std::min<std::size_t>(rng() % 40, stream.size() - fed);
      decoder.feed(std::string_view(stream).substr(fed, chunk));
      fed += chunk;
      const std::string seen = stream.substr(0, fed);
      for (;;) {
        const DecodeResult got = decoder.next();
        const Expected want = reference_next(seen, consumed, kLimit);
        ASSERT_EQ(got.status, want.status) << "trial " << trial << " at " << consumed;
        ASSERT_LE(got.payload.size(), kLimit);
        if (got.status == DecodeStatus::kFrame) {
          ASSERT_EQ(got.payload.size(), want.payload_size);
          ASSERT_LE(want.payload_begin + want.payload_size, fed);  // inside received bytes
          ASSERT_EQ(as_view(got.payload), seen.substr(want.payload_begin, want.payload_size));
          consumed = want.payload_begin + want.payload_size;
          ASSERT_EQ(decoder.buffered(), fed - consumed);
          ++frames_seen;
          continue;
        }
        if (got.status == DecodeStatus::kTooLarge) {
          ASSERT_EQ(got.announced_length, want.announced);
        }
        if (got.status != DecodeStatus::kNeedMore) {
          failed = true;
          ++failures_seen;
          // and it stays failed
          ASSERT_EQ(decoder.next().status, got.status);
        }
        break;
      }
      if (fed == stream.size()) break;
    }
  }
  // the generator must actually exercise both paths
  EXPECT_GT(frames_seen, 1000);
  EXPECT_GT(failures_seen, 500);
}

felt::v1::ClientMessage make_proxy_update() {
  felt::v1::ClientMessage message;
  message.set_request_id(42);
  felt::v1::ProxyUpdate* update = message.mutable_proxy_update();
  update->set_proxy_id(3);
  update->mutable_position()->set_x(0.125);
  update->mutable_position()->set_y(-1.5);
  update->mutable_position()->set_z(1e-3);
  update->set_buttons(1);
  update->set_client_time_us(1'700'000'000'123'456ULL);
  return message;
}

TEST(MessageCodec, ProxyUpdateRoundTrips) {
  const felt::v1::ClientMessage sent = make_proxy_update();
  std::string stream;
  append_message(stream, sent);

  FrameDecoder decoder(1 << 16);
  decoder.feed(stream);
  const DecodeResult r = decoder.next();
  ASSERT_EQ(r.status, DecodeStatus::kFrame);
  EXPECT_EQ(decoder.buffered(), 0u);

  felt::v1::ClientMessage received;
  ASSERT_TRUE(parse_message(r.payload, received));
  ASSERT_TRUE(received.has_proxy_update());
  EXPECT_EQ(received.request_id(), 42u);
  EXPECT_EQ(received.proxy_update().proxy_id(), 3u);
  EXPECT_EQ(received.proxy_update().position().x(), 0.125);
  EXPECT_EQ(received.proxy_update().position().y(), -1.5);
  EXPECT_EQ(received.proxy_update().position().z(), 1e-3);
  EXPECT_EQ(received.proxy_update().buttons(), 1u);
  EXPECT_EQ(received.proxy_update().client_time_us(), 1'700'000'000'123'456ULL);
}

TEST(MessageCodec, MatchesProtobufDelimitedFormat) {
  // the frame must be byte-identical to what protobuf's writeDelimitedTo produces
  const felt::v1::ClientMessage message = make_proxy_update();
  std::string ours;
  append_message(ours, message);
  std::string theirs;
  {
    google::protobuf::io::StringOutputStream out(&theirs);
    ASSERT_TRUE(google::protobuf::util::SerializeDelimitedToZeroCopyStream(message, &out));
  }
  EXPECT_EQ(ours, theirs);
}

TEST(MessageCodec, SeveralMessagesDecodeInOrder) {
  std::string stream;
  for (std::uint64_t id = 1; id <= 5; ++id) {
    felt::v1::ClientMessage m;
    m.set_request_id(id);
    m.mutable_hello()->set_client_name(std::string(id * 50, 'n'));
    append_message(stream, m);
  }
  FrameDecoder decoder(1 << 16);
  decoder.feed(stream);
  for (std::uint64_t id = 1; id <= 5; ++id) {
    const DecodeResult r = decoder.next();
    ASSERT_EQ(r.status, DecodeStatus::kFrame);
    felt::v1::ClientMessage m;
    ASSERT_TRUE(parse_message(r.payload, m));
    EXPECT_EQ(m.request_id(), id);
    EXPECT_EQ(m.hello().client_name(), std::string(id * 50, 'n'));
  }
  EXPECT_EQ(decoder.next().status, DecodeStatus::kNeedMore);
}

TEST(MessageCodec, EmptyMessageIsAnEmptyFrame) {
  std::string stream;
  append_message(stream, felt::v1::ClientMessage());
  EXPECT_EQ(stream, bytes({0x00}));
  felt::v1::ClientMessage m;
  m.set_request_id(9);  // parsing must replace, not merge into, what was there
  EXPECT_TRUE(parse_message({}, m));
  EXPECT_EQ(m.request_id(), 0u);
}

TEST(MessageCodec, TruncatedStringFieldFailsToParse) {
  // the only field is `hello`, a length-delimited field holding a string field, so every cut
  // strictly inside the payload ends inside a length-delimited field
  felt::v1::ClientMessage message;
  message.mutable_hello()->set_client_name("a client with a longish name");
  std::string payload;
  ASSERT_TRUE(message.SerializeToString(&payload));
  ASSERT_GT(payload.size(), 4u);

  const auto* data = reinterpret_cast<const std::uint8_t*>(payload.data());
  felt::v1::ClientMessage whole;
  ASSERT_TRUE(parse_message(std::span(data, payload.size()), whole));
  EXPECT_EQ(whole.hello().client_name(), "a client with a longish name");

  for (std::size_t cut = 1; cut < payload.size(); ++cut) {
    felt::v1::ClientMessage parsed;
    EXPECT_FALSE(parse_message(std::span(data, cut), parsed)) << "cut at " << cut;
  }
}

}  // namespace
}  // namespace felt::wire
