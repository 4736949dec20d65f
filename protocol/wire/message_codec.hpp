#pragma once
// Protobuf messages on top of the frame codec: serialize into a frame, parse a frame.

#include <span>
#include <string>

#include <google/protobuf/message_lite.h>

namespace felt::wire {

/// Appends `message` as one length-delimited frame.
void append_message(std::string& out, const google::protobuf::MessageLite& message);

/// Parses one frame's payload into `message`; false when the bytes are not such a message.
bool parse_message(std::span<const std::uint8_t> payload, google::protobuf::MessageLite& message);

}  // namespace felt::wire
