#pragma once
// What a session's connection carries: felt.v1 messages in and out, over TCP (each message
// behind a varint length) or a WebSocket (one binary message each). A Session is the same for
// every transport: greeting, limits, ownership, events, frames and the reply backlog live there,
// and only the bytes on the wire differ.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include <boost/asio/any_io_executor.hpp>
#include <boost/system/error_code.hpp>

#include "wire/frame_codec.hpp"

namespace felt::net {

class Transport {
 public:
  using Executor = boost::asio::any_io_executor;
  using ReadHandler = std::function<void(const boost::system::error_code&, std::size_t bytes)>;
  using WriteHandler = std::function<void(const boost::system::error_code&)>;

  virtual ~Transport() = default;

  /// The connection's strand: every call below is made on it, and every handler runs on it.
  virtual const Executor& executor() const = 0;

  /// Reads more of what the client sends; `done` gets the bytes read, or why nothing more will
  /// come.
  virtual void receive(ReadHandler done) = 0;
  /// The next whole message received, or why there is none: kNeedMore (receive() more),
  /// kTooLarge (over the limit; announced_length is its size, 0 when unknown) or kBadPrefix
  /// (bytes that cannot be a message). After kTooLarge or kBadPrefix nothing more is read.
  virtual wire::DecodeResult next() = 0;

  /// Sends `frames`: ServerMessages, each behind its varint length, back to back (the form the
  /// session queues them in). Returns true when all were handed to the kernel at once (or `ec`
  /// says why not); false when the rest goes out later: `done` is then called once it has, and
  /// `frames` must stay as it is until then.
  virtual bool send(const std::string& frames, WriteHandler done,
                    boost::system::error_code& ec) = 0;

  /// Ends the connection at once.
  virtual void close() = 0;
  /// Ends the connection after what was sent (the WebSocket closing handshake).
  virtual void finish() = 0;
  virtual bool is_open() const = 0;

  /// Where the connection comes from, as the log names it: "127.0.0.1:40112 over TCP".
  virtual const std::string& peer() const = 0;
};

}  // namespace felt::net
