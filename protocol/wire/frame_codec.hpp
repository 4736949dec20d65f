#pragma once
// Length-delimited framing as protobuf writes it (writeDelimitedTo): a base-128 varint byte
// count, then that many bytes. Pure: bytes in, frames out, no sockets, so it is unit-tested and
// fuzzed on its own and shared by the server and the client.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace felt::wire {

/// Largest varint a length prefix may take (a 64-bit value).
inline constexpr std::size_t kMaxVarintBytes = 10;

/// Appends `value` as a base-128 varint.
void append_varint(std::string& out, std::uint64_t value);

/// Appends one frame: the varint length of `payload`, then `payload`.
void append_frame(std::string& out, std::string_view payload);

/// A frame at the front of a buffer: its payload, and the bytes it takes with its prefix.
struct FrameView {
  std::string_view payload;
  std::size_t size = 0;
};

/// The whole frame that `frames` (frames back to back, as append_frame writes them) starts
/// with; nothing when it does not start with one.
std::optional<FrameView> first_frame(std::string_view frames);

enum class DecodeStatus {
  kFrame,     ///< a whole frame is available in DecodeResult::payload
  kNeedMore,  ///< the buffered bytes end inside a length prefix or a payload
  kTooLarge,  ///< the length prefix exceeds the limit; the stream cannot be resynchronised
  kBadPrefix  ///< the length prefix is not a valid varint (more than 10 bytes)
};

struct DecodeResult {
  DecodeStatus status = DecodeStatus::kNeedMore;
  /// The frame's bytes; valid until the next call to feed() or next().
  std::span<const std::uint8_t> payload;
  /// With kTooLarge, the length the prefix announced.
  std::uint64_t announced_length = 0;
};

/// Splits a byte stream into frames. Nothing is allocated for an announced length: the buffer
/// only ever holds bytes that were actually received.
class FrameDecoder {
 public:
  explicit FrameDecoder(std::size_t max_frame_bytes);

  /// Appends received bytes.
  void feed(std::span<const std::uint8_t> bytes);
  void feed(std::string_view bytes);

  /// The next frame, or why there is none. After kTooLarge or kBadPrefix the decoder stays in
  /// that state: the connection has to be closed.
  DecodeResult next();

  /// Bytes received and not yet returned as frames.
  std::size_t buffered() const { return buffer_.size() - read_; }
  std::size_t max_frame_bytes() const { return max_frame_bytes_; }

 private:
  std::size_t max_frame_bytes_;
  std::vector<std::uint8_t> buffer_;
  std::size_t read_ = 0;
  DecodeStatus failure_ = DecodeStatus::kNeedMore;
};

}  // namespace felt::wire
