#pragma once
// Opens an acceptor on HOST:PORT, for the TCP port and the web port alike.

#include <cstdint>
#include <expected>
#include <string>

#include <boost/asio/ip/tcp.hpp>

namespace felt::net {

/// Resolves `host` (numeric), binds `acceptor` to it and `port` (0 picks a free port) and
/// listens. Returns the bound endpoint, or why not.
std::expected<boost::asio::ip::tcp::endpoint, std::string> bind_acceptor(
    boost::asio::ip::tcp::acceptor& acceptor, const std::string& host, std::uint16_t port);

}  // namespace felt::net
