#include "net/outbound_queue.hpp"

#include "wire/message_codec.hpp"

namespace felt::net {

namespace {

/// The reply buffer kept between writes, bytes: ForceUpdates and the usual replies fit many
/// times over.
constexpr std::size_t kKeptReplyCapacity = 64 * 1024;

}  // namespace

OutboundQueue::OutboundQueue(Transport& transport, Listener& listener,
                             std::size_t max_backlog_bytes)
    : transport_(transport), listener_(listener), max_backlog_bytes_(max_backlog_bytes) {}

void OutboundQueue::push(const felt::v1::ServerMessage& message) {
  if (stopped_ || !transport_.is_open()) return;
  const bool backlog = !queued_.empty();
  wire::append_message(queued_, message);
  // one reply larger than the backlog on its own (a big saved state) still goes out
  if (queued_.size() > max_backlog_bytes_ && backlog) {
    // the client does not read its replies; dropping them would break the protocol
    std::string().swap(queued_);
    stop();
    listener_.on_backlog_exceeded(max_backlog_bytes_);
    return;
  }
  write();
}

void OutboundQueue::put_frame(std::string frame) {
  if (stopped_ || closing_) return;
  frame_ = std::move(frame);
  frame_waiting_ = true;
  write();
}

void OutboundQueue::drop_frame() {
  frame_waiting_ = false;
  frame_.clear();
}

void OutboundQueue::close_after_queued() {
  closing_ = true;
  drop_frame();
  write();
}

void OutboundQueue::stop() {
  stopped_ = true;
  drop_frame();
}

void OutboundQueue::write() {
  while (!writing_ && !stopped_ && transport_.is_open()) {
    if (!queued_.empty()) {
      // every queued reply goes out in one write, and the buffer written last takes their
      // place; one grown past what replies usually need (a burst, a frame) is let go
      writing_bytes_.swap(queued_);
      queued_.clear();
      if (queued_.capacity() > kKeptReplyCapacity) std::string().swap(queued_);
    } else if (frame_waiting_ && !closing_) {
      writing_bytes_.swap(frame_);
      frame_waiting_ = false;
      listener_.on_frame_written();
    } else {
      if (closing_) listener_.on_drained();
      return;
    }
    bytes_sent_ += writing_bytes_.size();
    boost::system::error_code ec;
    const bool done = transport_.send(
        writing_bytes_,
        [this, owner = owner_.lock()](const boost::system::error_code& error) {
          writing_ = false;
          if (error) {
            stop();
            listener_.on_connection_lost();
            return;
          }
          write();
        },
        ec);
    if (ec) {
      stop();
      listener_.on_connection_lost();
      return;
    }
    writing_ = !done;
  }
}

}  // namespace felt::net
