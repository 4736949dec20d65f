#pragma once
// How a scene names a haptic proxy: each client numbers its own proxies, so a proxy is known by
// its client and its number there.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "ids/strong_id.hpp"
#include "runtime/client_id.hpp"

namespace felt {

/// A proxy's number among its client's proxies (OpenProxy's reply, ProxyUpdate.proxy_id).
using ProxyId = StrongId<struct ProxyIdTag, std::uint32_t>;

/// A proxy among all of a scene's: the client that opened it and its number there.
struct ProxyKey {
  ClientId client = 0;
  ProxyId proxy = 0;
  friend bool operator==(const ProxyKey&, const ProxyKey&) = default;
  friend auto operator<=>(const ProxyKey&, const ProxyKey&) = default;
};

}  // namespace felt

template <>
struct std::hash<felt::ProxyKey> {
  std::size_t operator()(const felt::ProxyKey& key) const noexcept {
    return std::hash<std::uint64_t>{}(std::uint64_t{key.client.value()} << 32 | key.proxy.value());
  }
};
