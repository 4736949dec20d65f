#pragma once
// How fast one client's requests are read (--max-request-rate): a token bucket that fills at
// the rate up to a burst, so a client may send a short burst at any speed but no more than the
// rate for long. Every request counts, answered at once or later, since each costs the network
// thread its handling; a client with no token left waits (its requests stay in its connection,
// none is refused or lost) while everyone else is served.

#include <chrono>

namespace felt::net {

class RequestRate {
 public:
  using Clock = std::chrono::steady_clock;

  /// `per_second` > 0 tokens a second, at most `burst` (>= 1) held; full at `now`.
  RequestRate(double per_second, double burst, Clock::time_point now);

  /// How long from `now` until a request may be read: zero when one may be read now.
  Clock::duration wait(Clock::time_point now);
  /// Counts a request read (after a zero wait).
  void take() { tokens_ -= 1; }

 private:
  double per_second_;
  double burst_;
  double tokens_;
  Clock::time_point filled_;  ///< when tokens_ was last brought up to date
};

/// The burst a rate allows: a tenth of a second's requests, and at least 32 (a session's turn on
/// its network thread).
double request_burst(double per_second);

}  // namespace felt::net
