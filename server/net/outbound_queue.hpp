#pragma once
// What a session sends, in the order it goes: replies and events, queued back to back and never
// dropped (a client that lets more than the backlog pile up unread is dropped instead), and
// one slot for the latest frame, written only when no reply waits. A slow reader costs the
// server one frame and its unread replies; it always gets the newest frame.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "felt/v1/envelope.pb.h"
#include "net/transport.hpp"

namespace felt::net {

class OutboundQueue {
 public:
  /// What the queue tells its session, on the strand.
  class Listener {
   public:
    /// The frame in the slot was handed to the transport.
    virtual void on_frame_written() = 0;
    /// A write failed: the connection must end now.
    virtual void on_connection_lost() = 0;
    /// The client let more than the backlog pile up unread: the connection must end now.
    virtual void on_backlog_exceeded(std::size_t max_backlog_bytes) = 0;
    /// close_after_queued() was called and everything queued has gone out.
    virtual void on_drained() = 0;

   protected:
    ~Listener() = default;
  };

  /// `owner` (the session) is kept alive while a write is under way.
  OutboundQueue(Transport& transport, Listener& listener, std::size_t max_backlog_bytes);
  void set_owner(std::weak_ptr<void> owner) { owner_ = std::move(owner); }

  /// Queues a reply or an event, and writes it unless a write is under way.
  void push(const felt::v1::ServerMessage& message);
  /// Puts an encoded frame (a length-delimited ServerMessage) into the slot, replacing one that
  /// waits there, and writes it when nothing else waits.
  void put_frame(std::string frame);
  bool frame_waiting() const { return frame_waiting_; }
  /// Empties the slot: the frame there is not sent.
  void drop_frame();
  /// Sends no frame any more; once every queued reply is written, on_drained().
  void close_after_queued();
  bool closing() const { return closing_; }
  /// Stops: nothing more is written (the connection is gone).
  void stop();

  std::size_t queued_bytes() const { return queued_.size(); }
  std::uint64_t bytes_sent() const { return bytes_sent_; }

 private:
  /// Hands what waits to the transport, replies before the frame, until a write is left under
  /// way or nothing waits.
  void write();

  Transport& transport_;
  Listener& listener_;
  const std::size_t max_backlog_bytes_;
  std::weak_ptr<void> owner_;
  /// replies and events not yet handed to the transport, back to back as length-delimited
  /// frames: they go out in one write, and cost their bytes and no allocation each
  std::string queued_;
  std::string frame_;  ///< latest wins: a newer frame replaces one not yet written
  bool frame_waiting_ = false;
  std::string writing_bytes_;  ///< what the transport is sending
  bool writing_ = false;
  bool closing_ = false;
  bool stopped_ = false;
  std::uint64_t bytes_sent_ = 0;
};

}  // namespace felt::net
