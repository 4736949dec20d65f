// parse_host_port on the forms the command lines accept and on malformed input.

#include <string_view>

#include <gtest/gtest.h>

#include "wire/host_port.hpp"

namespace felt::wire {
namespace {

TEST(HostPort, ParsesIpv4AndPort) {
  const auto hp = parse_host_port("127.0.0.1:7450");
  ASSERT_TRUE(hp.has_value()) << hp.error();
  EXPECT_EQ(hp->host, "127.0.0.1");
  EXPECT_EQ(hp->port, 7450);
}

TEST(HostPort, ParsesNameAndPortZero) {
  // port 0 asks the OS for a free port, so it must be accepted
  const auto hp = parse_host_port("localhost:0");
  ASSERT_TRUE(hp.has_value()) << hp.error();
  EXPECT_EQ(hp->host, "localhost");
  EXPECT_EQ(hp->port, 0);
}

TEST(HostPort, StripsBracketsFromIpv6) {
  const auto hp = parse_host_port("[::1]:80");
  ASSERT_TRUE(hp.has_value()) << hp.error();
  EXPECT_EQ(hp->host, "::1");
  EXPECT_EQ(hp->port, 80);

  const auto full = parse_host_port("[2001:db8::7]:7450");
  ASSERT_TRUE(full.has_value()) << full.error();
  EXPECT_EQ(full->host, "2001:db8::7");
  EXPECT_EQ(full->port, 7450);
}

TEST(HostPort, AcceptsLargestPort) {
  const auto hp = parse_host_port("0.0.0.0:65535");
  ASSERT_TRUE(hp.has_value()) << hp.error();
  EXPECT_EQ(hp->host, "0.0.0.0");
  EXPECT_EQ(hp->port, 65535);
}

TEST(HostPort, RejectsMalformedInput) {
  for (std::string_view text : {"nohost", ":80", "h:", "h:65536", "h:12x", "h:-1", "", ":", "[]:80",
                                "h:99999999999999999999", "h: 80", "h:+80", "h:0x50"}) {
    const auto hp = parse_host_port(text);
    EXPECT_FALSE(hp.has_value()) << "accepted \"" << text << "\" as " << hp->host << " port "
                                 << hp->port;
    if (!hp) {
      EXPECT_FALSE(hp.error().empty()) << text;
    }
  }
}

TEST(HostPort, ErrorNamesTheInput) {
  // the message is shown to a user who mistyped an argument
  const auto hp = parse_host_port("h:65536");
  ASSERT_FALSE(hp.has_value());
  EXPECT_NE(hp.error().find("h:65536"), std::string::npos) << hp.error();
}

}  // namespace
}  // namespace felt::wire
