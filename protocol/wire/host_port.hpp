#pragma once
// "HOST:PORT" as the command lines of feltd and felt take it ("[::1]:7450" for IPv6).

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

namespace felt::wire {

struct HostPort {
  std::string host;
  std::uint16_t port = 0;
};

std::expected<HostPort, std::string> parse_host_port(std::string_view text);

}  // namespace felt::wire
