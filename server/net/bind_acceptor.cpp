#include "net/bind_acceptor.hpp"

namespace felt::net {

namespace asio = boost::asio;
using asio::ip::tcp;

std::expected<tcp::endpoint, std::string> bind_acceptor(tcp::acceptor& acceptor,
                                                        const std::string& host,
                                                        std::uint16_t port) {
  boost::system::error_code ec;
  tcp::resolver resolver(acceptor.get_executor());
  const auto results = resolver.resolve(
      host, std::to_string(port), tcp::resolver::numeric_service | tcp::resolver::passive, ec);
  if (ec || results.empty()) return std::unexpected("cannot resolve " + host + ": " + ec.message());
  const tcp::endpoint endpoint = results.begin()->endpoint();
  acceptor.open(endpoint.protocol(), ec);
  if (!ec) acceptor.set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) acceptor.bind(endpoint, ec);
  if (!ec) acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    return std::unexpected("cannot listen on " + endpoint.address().to_string() + ":" +
                           std::to_string(port) + ": " + ec.message());
  }
  return acceptor.local_endpoint();
}

}  // namespace felt::net
