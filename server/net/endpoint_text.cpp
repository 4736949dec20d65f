#include "net/endpoint_text.hpp"

namespace felt::net {

std::string endpoint_text(const boost::asio::ip::tcp::endpoint& endpoint) {
  const auto ip = endpoint.address();
  return (ip.is_v6() ? "[" + ip.to_string() + "]" : ip.to_string()) + ":" +
         std::to_string(endpoint.port());
}

}  // namespace felt::net
