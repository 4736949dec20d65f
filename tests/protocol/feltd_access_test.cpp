// Who may reach feltd: a token when one is configured (from the flag or the environment), and
// only loopback unless told otherwise.

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <optional>

#include <gtest/gtest.h>

#include "feltd_fixture.hpp"

namespace felt::test {
namespace {

TEST(Feltd, TokenIsRequiredWhenConfigured) {
  auto args = default_args();
  args.insert(args.end(), {"--token", "sesame"});
  FeltdProcess server(args);
  {
    Client client;
    client.connect("127.0.0.1", server.port());
    try {
      client.hello("intruder", "open");
      FAIL() << "a wrong token was accepted";
    } catch (const ClientError& e) {
      EXPECT_EQ(e.code(), v1::ERROR_CODE_UNAUTHORIZED);
    }
    EXPECT_THROW(client.subscribe_frames(), ClientError);  // still not greeted
    EXPECT_EQ(client.hello("friend", "sesame").protocol_version(), 1u);
  }
  {
    // no endless guessing: the third wrong token closes the connection
    Client guesser;
    guesser.connect("127.0.0.1", server.port());
    for (const char* guess : {"a", "b"}) {
      expect_error([&] { guesser.hello("guesser", guess); }, v1::ERROR_CODE_UNAUTHORIZED);
    }
    expect_error([&] { guesser.hello("guesser", "c"); }, v1::ERROR_CODE_UNAUTHORIZED);
    EXPECT_THROW(guesser.hello("guesser", "sesame"), ClientError);  // closed
  }
  EXPECT_EQ(server.stop(SIGINT, 5s), 0);
}

/// Sets an environment variable while it lives (feltd children inherit the environment).
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
  ~ScopedEnvironment() { unsetenv(name_); }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  const char* name_;
};

TEST(Feltd, TheTokenCanComeFromTheEnvironmentAndTheFlagWins) {
  const auto token_needed = [](FeltdProcess& server, const std::string& token) {
    Client client;
    client.connect("127.0.0.1", server.port());
    expect_error([&] { client.hello("intruder"); }, v1::ERROR_CODE_UNAUTHORIZED);
    EXPECT_EQ(client.hello("friend", token).protocol_version(), 1u);
  };
  ScopedEnvironment environment("FELT_TOKEN", "from-the-environment");
  FeltdProcess from_environment(default_args());
  token_needed(from_environment, "from-the-environment");
  auto args = default_args();
  args.insert(args.end(), {"--token", "from-the-flag"});
  FeltdProcess from_flag(args);
  {
    Client client;
    client.connect("127.0.0.1", from_flag.port());
    expect_error([&] { client.hello("guesser", "from-the-environment"); },
                 v1::ERROR_CODE_UNAUTHORIZED);
  }
  token_needed(from_flag, "from-the-flag");
}

/// Whether a TCP connection to `address`:`port` (IPv4, network order) is accepted.
bool accepts(in_addr address, std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr = address;
  const bool connected = ::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) == 0;
  ::close(fd);
  return connected;
}

TEST(Feltd, ListensOnLoopbackOnlyByDefault) {
  constexpr std::uint16_t kDefaultPort = 7450;
  std::optional<FeltdProcess> server;
  try {
    server.emplace(default_args(), true);
  } catch (const std::runtime_error& e) {
    // a server that did not come up because another holds the port says nothing of the default
    in_addr loopback{htonl(INADDR_LOOPBACK)};
    if (std::string(e.what()).starts_with("feltd exited") && accepts(loopback, kDefaultPort)) {
      GTEST_SKIP() << "port 7450 is in use";
    }
    FAIL() << e.what();  // listening elsewhere than on 127.0.0.1 is one of these
  }
  EXPECT_EQ(server->first_line(), "listening on 127.0.0.1:7450");
  Client local;
  local.connect("127.0.0.1", kDefaultPort);
  EXPECT_EQ(local.hello("local").protocol_version(), 1u);
  // the machine's other IPv4 addresses (a container has its own) do not reach it
  ifaddrs* interfaces = nullptr;
  ASSERT_EQ(getifaddrs(&interfaces), 0);
  for (const ifaddrs* i = interfaces; i; i = i->ifa_next) {
    if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET || (i->ifa_flags & IFF_LOOPBACK) ||
        !(i->ifa_flags & IFF_UP)) {
      continue;
    }
    const in_addr address = reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr;
    EXPECT_FALSE(accepts(address, kDefaultPort)) << inet_ntoa(address);
  }
  freeifaddrs(interfaces);
}

}  // namespace
}  // namespace felt::test
