#pragma once
// An endpoint as a URL or a log names it: 127.0.0.1:7450, [::1]:7450.

#include <string>

#include <boost/asio/ip/tcp.hpp>

namespace felt::net {

std::string endpoint_text(const boost::asio::ip::tcp::endpoint& endpoint);

}  // namespace felt::net
