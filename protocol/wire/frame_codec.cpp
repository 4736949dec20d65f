#include "wire/frame_codec.hpp"

#include <algorithm>

namespace felt::wire {

void append_varint(std::string& out, std::uint64_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7f) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

void append_frame(std::string& out, std::string_view payload) {
  append_varint(out, payload.size());
  out.append(payload);
}

std::optional<FrameView> first_frame(std::string_view frames) {
  std::uint64_t length = 0;
  for (std::size_t i = 0; i < std::min(frames.size(), kMaxVarintBytes); ++i) {
    const auto byte = static_cast<std::uint8_t>(frames[i]);
    length |= static_cast<std::uint64_t>(byte & 0x7f) << (7 * i);
    if ((byte & 0x80) != 0) continue;
    if (frames.size() - (i + 1) < length) return std::nullopt;
    return FrameView{frames.substr(i + 1, length), i + 1 + length};
  }
  return std::nullopt;
}

FrameDecoder::FrameDecoder(std::size_t max_frame_bytes) : max_frame_bytes_(max_frame_bytes) {}

void FrameDecoder::feed(std::span<const std::uint8_t> bytes) {
  // drop consumed bytes before growing, so the buffer stays near one frame plus one read
  if (read_ > 0 && (read_ == buffer_.size() || read_ >= buffer_.size() / 2)) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(read_));
    read_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

void FrameDecoder::feed(std::string_view bytes) {
  feed(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
}

DecodeResult FrameDecoder::next() {
  if (failure_ != DecodeStatus::kNeedMore) return {failure_, {}, 0};

  std::uint64_t length = 0;
  std::size_t pos = read_;
  for (std::size_t i = 0;; ++i) {
    if (i == kMaxVarintBytes) {
      failure_ = DecodeStatus::kBadPrefix;
      return {failure_, {}, 0};
    }
    if (pos == buffer_.size()) return {DecodeStatus::kNeedMore, {}, 0};
    const std::uint8_t byte = buffer_[pos++];
    length |= static_cast<std::uint64_t>(byte & 0x7f) << (7 * i);
    if ((byte & 0x80) == 0) break;
  }
  if (length > max_frame_bytes_) {
    failure_ = DecodeStatus::kTooLarge;
    return {failure_, {}, length};
  }
  if (buffer_.size() - pos < length) return {DecodeStatus::kNeedMore, {}, 0};

  read_ = pos + length;
  return {DecodeStatus::kFrame, std::span(buffer_).subspan(pos, length), 0};
}

}  // namespace felt::wire
