#include "wire/host_port.hpp"

#include <charconv>

namespace felt::wire {
namespace {

// built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here
std::string not_host_port(std::string_view text, std::string_view detail) {
  std::string message = "\"";
  message += text;
  message += "\" is not HOST:PORT";
  message += detail;
  return message;
}

}  // namespace

std::expected<HostPort, std::string> parse_host_port(std::string_view text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos || colon == 0) {
    return std::unexpected(not_host_port(text, ""));
  }
  std::string_view host = text.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  const std::string_view port_text = text.substr(colon + 1);
  unsigned port = 0;
  const auto [end, ec] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (host.empty() || port_text.empty() || ec != std::errc() ||
      end != port_text.data() + port_text.size() || port > 65535) {
    return std::unexpected(not_host_port(text, " with a port 0-65535"));
  }
  return HostPort{std::string(host), static_cast<std::uint16_t>(port)};
}

}  // namespace felt::wire
